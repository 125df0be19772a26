// Sync mode end to end (docs/sync.md): tools/launch.sh --sync with both demo
// teams as sync clients, over real LCM multicast (own network namespace:
// tests/run_isolated.sh). Runs are short (a few seconds of sim time, about a
// second of wall time each).
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <cmath>
#include <regex>
#include <set>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/sim_commands_t.hpp>
#include <ubersim/vision_frame_t.hpp>

#include "e2e_support.hpp"
#include "read_file.hpp"
#include "sync_logs.hpp"

using namespace e2e;
using ubersim::test::ChildProcess;

namespace {

struct GameRun {
  int status = -1;
  std::string output;
  std::map<std::string, ChannelLog> log;
  std::string radio_log;
};

using ubersim::test::read_file;

// One game in sync mode, recorded; the script ends it after `duration` s of sim time.
GameRun run_game(const TempDir& dir, const std::string& name, std::vector<std::string> options) {
  GameRun run;
  const std::string log = dir.path(name + ".lcmlog");
  options.insert(options.end(),
                 {"--sync", "--demo", "both", "--log", log, "--log-dir", dir.path(name + "_logs")});
  Launch launch(options, dir);
  run.status = launch.script().wait(120);
  run.output = launch.output();
  run.radio_log = read_file(dir.path(name + "_logs/radio.log"));
  if (run.status == 0) run.log = read_log_by_channel(log);
  return run;
}

void expect_same_channels(const GameRun& a, const GameRun& b) {
  for (const std::string& channel : reproducible_channels()) {
    ASSERT_TRUE(a.log.count(channel)) << channel << " was not recorded";
    ASSERT_TRUE(b.log.count(channel)) << channel << " was not recorded";
    EXPECT_GT(a.log.at(channel).size(), 10u) << channel;
    EXPECT_EQ(compare_channel(a.log.at(channel), b.log.at(channel)), "") << "on " << channel;
  }
  for (int team : {0, 1}) {
    const ChannelLog first = team_only(a.log.at("SIM_COMMANDS"), team);
    EXPECT_GT(first.size(), 10u);
    EXPECT_EQ(compare_channel(first, team_only(b.log.at("SIM_COMMANDS"), team)), "")
        << "on SIM_COMMANDS, team " << team;
  }
}

}  // namespace

// Two runs with the same seeds, one of them next to a CPU hog, record the
// same bytes on every reproducible channel; a third with another seed does not.
TEST(Sync, SameSeedsGiveByteIdenticalLogsEvenUnderLoad) {
  TempDir dir;
  const std::vector<std::string> options{"--duration", "4", "--seed", "7", "--truth-every-step"};
  const GameRun quiet = run_game(dir, "quiet", options);
  ASSERT_EQ(quiet.status, 0) << quiet.output;
  GameRun loaded;
  {
    CpuHog hog;
    loaded = run_game(dir, "loaded", options);
  }
  ASSERT_EQ(loaded.status, 0) << loaded.output;
  expect_same_channels(quiet, loaded);

  // One step, one state: 4 s at 240 Hz and the state at 0.
  EXPECT_EQ(quiet.log.at("SIM_STATE").size(), 4u * 240u + 1u);
  EXPECT_NE(quiet.radio_log.find("0 client timeouts"), std::string::npos) << quiet.radio_log;

  // The comparison can fail: another vision and radio seed changes the game.
  const GameRun other =
      run_game(dir, "other", {"--duration", "4", "--seed", "8", "--truth-every-step"});
  ASSERT_EQ(other.status, 0) << other.output;
  EXPECT_NE(compare_channel(quiet.log.at("VISION"), other.log.at("VISION")), "");
}

// Every frame is answered, and every answer arrives when its frame was
// published: capture + the vision latency (66 ms +- 2 ms jitter, on the next
// physics step), then takes effect a radio latency (33 ms +- 2 ms) later.
TEST(Sync, AnswersTakeEffectAfterExactlyTheEmulatedLatency) {
  TempDir dir;
  const GameRun run = run_game(dir, "game", {"--duration", "3"});
  ASSERT_EQ(run.status, 0) << run.output;
  const auto frames = decode_all<ubersim::vision_frame_t>(run.log.at("VISION"));
  const auto answers = decode_all<ubersim::radio_packet_t>(run.log.at("RADIO_YELLOW"));
  const auto forwarded = decode_all<ubersim::sim_commands_t>(run.log.at("SIM_COMMANDS"));
  ASSERT_GT(frames.size(), 80u);
  EXPECT_EQ(answers.size(), frames.size()) << "one answer per frame";
  std::map<std::int64_t, double> t_sent_of;  // yellow packets by sequence
  for (const auto& a : answers) t_sent_of[a.sequence] = a.t_sent;
  int checked = 0;
  for (const auto& c : forwarded) {
    if (c.team != 0) continue;
    ASSERT_TRUE(t_sent_of.count(c.sequence));
    const double vision_latency = c.t_received - t_sent_of[c.sequence];
    EXPECT_GE(vision_latency, 0.066 - 4 * 0.002);
    EXPECT_LE(vision_latency, 0.066 + 4 * 0.002 + 1.0 / 240);
    // Whole steps: the frame went out at a physics step.
    EXPECT_NEAR(std::fmod(c.t_received * 240 + 0.5, 1.0), 0.5, 1e-6);
    const double radio_latency = c.t_apply - c.t_received;
    EXPECT_GE(radio_latency, 0.033 - 4 * 0.002);
    EXPECT_LE(radio_latency, 0.033 + 4 * 0.002);
    ++checked;
  }
  EXPECT_GT(checked, 60);
}

// With the ideal profiles (no latency) sync mode is a per-frame lockstep: each
// answer takes effect at the very step its frame was captured.
TEST(Sync, IdealProfilesGiveAPerFrameLockstep) {
  TempDir dir;
  const GameRun run = run_game(dir, "ideal", {"--duration", "2", "--profile", "ideal"});
  ASSERT_EQ(run.status, 0) << run.output;
  const auto answers = decode_all<ubersim::radio_packet_t>(run.log.at("RADIO_BLUE"));
  const auto forwarded = decode_all<ubersim::sim_commands_t>(run.log.at("SIM_COMMANDS"));
  std::map<std::int64_t, double> t_sent_of;
  for (const auto& a : answers) t_sent_of[a.sequence] = a.t_sent;
  int checked = 0;
  for (const auto& c : forwarded) {
    if (c.team != 1) continue;
    EXPECT_EQ(c.t_apply, t_sent_of.at(c.sequence)) << "answer " << c.sequence;
    ++checked;
  }
  EXPECT_GT(checked, 50);
}

bool wait_for_text(const std::string& path, const std::string& text, double timeout_s) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < deadline) {
    if (read_file(path).find(text) != std::string::npos) return true;
    ::usleep(20000);
  }
  return false;
}

// A client that stops answering (SIGSTOP) is dropped after the timeout and
// the run goes on; with --sync-strict the run fails instead.
TEST(Sync, SilentClientIsDroppedOrFailsTheRunWhenStrict) {
  for (bool strict : {false, true}) {
    SCOPED_TRACE(strict ? "strict" : "not strict");
    TempDir dir;
    std::vector<std::string> options{"--sync", "--demo", "both", "--duration", "20"};
    if (strict) options.push_back("--sync-strict");
    Launch launch(options, dir);
    const auto pids = launch.processes();
    const std::string radio_log = dir.path("logs/radio.log");
    ASSERT_TRUE(wait_for_text(radio_log, "2 client(s) registered", 10)) << launch.output();
    ::kill(pids.at("demo_blue"), SIGSTOP);
    const bool dropped = wait_for_text(radio_log, "did not answer", 10);
    ::kill(pids.at("demo_blue"), SIGCONT);
    ASSERT_TRUE(dropped) << read_file(radio_log);
    const int status = launch.script().wait(60);
    if (strict) {
      EXPECT_NE(status, 0) << launch.output();
      EXPECT_NE(launch.output().find("radio exited with status 1"), std::string::npos)
          << launch.output();
    } else {
      EXPECT_EQ(status, 0) << launch.output();
      EXPECT_NE(launch.output().find("physics finished its 20 s"), std::string::npos)
          << launch.output();
    }
  }
}

// Ground truth on demand (the default; --truth-every-step is the old way): the states consumers
// asked for, and nothing else changes. Reproducible too, also under load.
TEST(Sync, TruthOnDemandSendsFewerStatesAndChangesNothingElse) {
  TempDir dir;
  const std::vector<std::string> on_demand{"--duration", "4", "--seed", "7"};  // the default
  std::vector<std::string> options = on_demand;
  options.push_back("--truth-every-step");
  const GameRun every_step = run_game(dir, "every_step", options);
  const GameRun quiet = run_game(dir, "quiet", on_demand);
  GameRun loaded;
  {
    CpuHog hog;
    loaded = run_game(dir, "loaded", on_demand);
  }
  ASSERT_EQ(every_step.status, 0) << every_step.output;
  ASSERT_EQ(quiet.status, 0) << quiet.output;
  ASSERT_EQ(loaded.status, 0) << loaded.output;
  expect_same_channels(quiet, loaded);
  for (const std::string& channel : reproducible_channels()) {
    if (channel == "SIM_STATE") continue;
    EXPECT_EQ(compare_channel(every_step.log.at(channel), quiet.log.at(channel)), "")
        << channel << " changed with ground truth on demand";
  }
  // Fewer states (captures, frame releases and radio feedback samples, about
  // 45 Hz instead of 240 Hz), each one byte for byte a state of the full run.
  const ChannelLog& some = quiet.log.at("SIM_STATE");
  const ChannelLog& all = every_step.log.at("SIM_STATE");
  EXPECT_LT(some.size(), all.size() / 4);
  std::set<std::vector<unsigned char>> known(all.begin(), all.end());
  for (const auto& state : some) EXPECT_TRUE(known.count(state)) << "a state not in the full run";
}
