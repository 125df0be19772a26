// The official ssl-game-controller referees a whole sync-mode game in its CI
// mode (docs/official_gc.md): tools/launch.sh --sync --demo both --referee
// official --game-controller $UBERSIM_SSL_GC, twice, once beside a CPU hog on
// every core. The GC cannot be built on CI machines: without UBERSIM_SSL_GC
// naming its binary the test exits 77, which CTest reports as skipped.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <set>
#include <ubersim/referee_t.hpp>
#include <ubersim/sim_state_t.hpp>

#include "e2e_support.hpp"
#include "read_file.hpp"
#include "sync_logs.hpp"

using namespace e2e;
using ubersim::referee_t;
using ubersim::test::ChildProcess;

namespace {

// A short game (2 x 12 s) whose seed has the GC decide a goal (the demo teams
// score one in the first half; shorter games with these seeds see none).
const std::vector<std::string> kGame{"--game-length", "24", "--seed", "3"};
const char* const kReproducible = "REFEREE|VISION|RADIO_.*|SIM_STATE";

std::string game_controller() {
  const char* path = std::getenv("UBERSIM_SSL_GC");
  return path == nullptr ? "" : path;
}

using ubersim::test::read_file;

struct GameRun {
  int status = -1;
  std::string output;
  std::string log;     // the LCM log
  std::string events;  // the link's event log
};

GameRun play(const TempDir& dir, const std::string& name) {
  GameRun run;
  run.log = dir.path(name + ".lcmlog");
  std::vector<std::string> options{"--sync",
                                   "--demo",
                                   "both",
                                   "--referee",
                                   "official",
                                   "--game-controller",
                                   game_controller(),
                                   "--log",
                                   run.log,
                                   "--log-dir",
                                   dir.path(name + "_logs")};
  options.insert(options.end(), kGame.begin(), kGame.end());
  Launch launch(options, dir);
  run.status = launch.script().wait(240);
  run.output = launch.output();
  run.events = read_file(dir.path(name + "_logs/events.jsonl"));
  return run;
}

// ubersim_log_compare over the channels sync mode makes reproducible: its
// exit status and what it printed.
std::pair<int, std::string> compare_logs(const TempDir& dir, const GameRun& a, const GameRun& b) {
  ChildProcess compare(
      {bin_dir() + "/ubersim_log_compare", "--channels", kReproducible, a.log, b.log},
      dir.path("compare.out"));
  const int status = compare.wait(60);
  return {status, compare.log()};
}

// The event log but for the wall time its result line ends with.
std::string without_wall_time(const std::string& events) {
  return std::regex_replace(events, std::regex(R"(, "wall_time": [0-9.]+)"), "");
}

std::vector<referee_t> referees(const GameRun& run) {
  return decode_all<referee_t>(read_log_by_channel(run.log).at("REFEREE"));
}

}  // namespace

// Two runs of a whole game under the official GC, one beside a CPU hog, record
// the same bytes on REFEREE, VISION, RADIO_* and SIM_STATE, up to the state
// the GC ended the game at; the game went through every stage of a game and
// the GC decided a goal.
TEST(OfficialGc, WholeGameTwiceByteIdenticalEvenUnderLoad) {
  TempDir dir;
  const GameRun quiet = play(dir, "quiet");
  ASSERT_EQ(quiet.status, 0) << quiet.output;
  GameRun loaded;
  {
    CpuHog hog;
    loaded = play(dir, "loaded");
  }
  ASSERT_EQ(loaded.status, 0) << loaded.output;
  EXPECT_NE(quiet.output.find("launch: the game is over"), std::string::npos) << quiet.output;

  const auto [status, comparison] = compare_logs(dir, quiet, loaded);
  EXPECT_EQ(status, 0) << comparison;
  for (const char* channel : {"REFEREE", "VISION", "RADIO_YELLOW", "RADIO_BLUE",
                              "RADIO_FEEDBACK_YELLOW", "RADIO_FEEDBACK_BLUE", "SIM_STATE"}) {
    EXPECT_NE(comparison.find(std::string(channel) + ": same ("), std::string::npos)
        << channel << " not compared:\n"
        << comparison;
  }
  EXPECT_EQ(without_wall_time(quiet.events), without_wall_time(loaded.events));

  // Every stage from the first half's preparation to the end, in order.
  const auto messages = referees(quiet);
  ASSERT_FALSE(messages.empty());
  std::vector<int> stages;
  for (const referee_t& m : messages) {
    if (stages.empty() || stages.back() != m.stage) stages.push_back(m.stage);
  }
  const std::vector<int> whole_game{
      referee_t::STAGE_FIRST_HALF_PRE,  referee_t::STAGE_FIRST_HALF,  referee_t::STAGE_HALF_TIME,
      referee_t::STAGE_SECOND_HALF_PRE, referee_t::STAGE_SECOND_HALF, referee_t::STAGE_POST_GAME};
  EXPECT_EQ(stages, whole_game);
  const referee_t& last = messages.back();
  EXPECT_TRUE(last.game_over);
  // The game's end is the log's end: physics holds at the state the GC ended it at.
  const auto states =
      decode_all<ubersim::sim_state_t>(read_log_by_channel(quiet.log).at("SIM_STATE"));
  ASSERT_FALSE(states.empty());
  EXPECT_DOUBLE_EQ(states.back().sim_time, last.sim_time);

  // The GC decided a goal or a foul (ubersim's detectors only report).
  EXPECT_GT(last.yellow_score + last.blue_score + last.yellow_fouls + last.blue_fouls, 0)
      << quiet.events;
  EXPECT_NE(quiet.events.find("\"event\": \"GOAL\""), std::string::npos) << quiet.events;
}

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  const std::string gc = game_controller();
  if (gc.empty()) {
    std::printf(
        "SKIPPED: UBERSIM_SSL_GC does not name the ssl-game-controller binary "
        "(../shared/tools/build-official-ssl-stack.sh builds it)\n");
    return 77;
  }
  std::ifstream binary(gc);
  if (!binary) {
    std::printf("SKIPPED: UBERSIM_SSL_GC='%s' is not a file\n", gc.c_str());
    return 77;
  }
  return RUN_ALL_TESTS();
}
