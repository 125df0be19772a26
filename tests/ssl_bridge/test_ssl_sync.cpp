// Sync mode through the SSL bridge (docs/sync.md): tools/launch.sh --sync
// --ssl-bridge, and two real SSL team processes (ssl_sync_team, SSL-Vision
// in, RobotControl out, nothing of ubersim) play a game. Every detection
// packet gets its answer, each answer reaches the radio stamped with its
// frame's capture time, and two runs with the same seeds record the same
// bytes. ISOLATED: own network namespace, so the league's ports are free.
#include <gtest/gtest.h>

#include <ubersim/radio_packet_t.hpp>
#include <ubersim/vision_frame_t.hpp>

#include "e2e_support.hpp"
#include "read_file.hpp"
#include "sync_logs.hpp"

using namespace e2e;
using ubersim::test::ChildProcess;

namespace {

struct SslGame {
  int status = -1;
  std::string output;  // the launch script's, then each team's
  std::map<std::string, ChannelLog> log;
  std::string bridge_log, radio_log;
};

using ubersim::test::read_file;

// One game of `seconds` s of sim time, both teams SSL programs, recorded.
SslGame play(const TempDir& dir, const std::string& name, const std::string& seed,
             const std::string& seconds) {
  SslGame game;
  const std::string log = dir.path(name + ".lcmlog");
  const std::string logs = dir.path(name + "_logs");
  // --sync-strict: a team that misses an answer fails the run.
  Launch launch({"--sync-strict", "--ssl-bridge", "--duration", seconds, "--seed", seed, "--log",
                 log, "--log-dir", logs},
                dir);
  launch.processes();
  // Physics holds at sim time 0 until both teams have said hello.
  std::vector<std::unique_ptr<ChildProcess>> teams;
  for (const char* team : {"yellow", "blue"}) {
    teams.push_back(std::make_unique<ChildProcess>(
        std::vector<std::string>{UBERSIM_SSL_SYNC_TEAM_EXE, "--team", team},
        dir.path(name + "_" + team + ".log")));
  }
  game.status = launch.script().wait(120);
  game.output = launch.output();
  for (auto& team : teams) {
    const int status = team->stop(5);
    game.output += team->log();
    if (status != 0) game.status = 100 + status;
  }
  game.bridge_log = read_file(logs + "/ssl_bridge.log");
  game.radio_log = read_file(logs + "/radio.log");
  if (game.status == 0) game.log = read_log_by_channel(log);
  return game;
}

}  // namespace

TEST(SslSync, SslTeamsPlayAReproducibleSyncGameThroughTheBridge) {
  TempDir dir;
  const SslGame first = play(dir, "first", "7", "3");
  ASSERT_EQ(first.status, 0) << first.output << first.bridge_log << first.radio_log;
  const SslGame second = play(dir, "second", "7", "3");
  ASSERT_EQ(second.status, 0) << second.output << second.bridge_log << second.radio_log;

  // Every detection frame was answered once, in order, by each team: the
  // bridge stamped the n-th RobotControl with the n-th frame's capture time.
  const auto frames = decode_all<ubersim::vision_frame_t>(first.log.at("VISION"));
  ASSERT_GT(frames.size(), 80u);
  for (const char* channel : {"RADIO_YELLOW", "RADIO_BLUE"}) {
    SCOPED_TRACE(channel);
    const auto answers = decode_all<ubersim::radio_packet_t>(first.log.at(channel));
    ASSERT_EQ(answers.size(), frames.size()) << "one answer per detection frame";
    int with_commands = 0;
    for (std::size_t i = 0; i < frames.size(); ++i) {
      ASSERT_EQ(answers[i].t_sent, frames[i].t_capture) << "answer " << i;
      ASSERT_EQ(answers[i].sequence, static_cast<int64_t>(i + 1)) << "answer " << i;
      // The team sends commands for every second packet, nothing for the others.
      if (answers[i].num_commands > 0) ++with_commands;
      if (i % 2 == 1) {
        EXPECT_EQ(answers[i].num_commands, 0) << "answer " << i;
      }
    }
    EXPECT_GT(with_commands, static_cast<int>(frames.size() / 2) - 5);
  }
  EXPECT_NE(first.radio_log.find("0 duplicated or out of order; 0 client timeouts"),
            std::string::npos)
      << first.radio_log;
  EXPECT_NE(first.bridge_log.find("extra=0 timeouts=0"), std::string::npos) << first.bridge_log;

  // Byte for byte the same game, channel by channel.
  for (const std::string& channel : reproducible_channels()) {
    ASSERT_TRUE(first.log.count(channel)) << channel << " was not recorded";
    ASSERT_TRUE(second.log.count(channel)) << channel << " was not recorded";
    EXPECT_GT(first.log.at(channel).size(), 10u) << channel;
    EXPECT_EQ(compare_channel(first.log.at(channel), second.log.at(channel)), "")
        << "on " << channel;
  }
  for (int team : {0, 1}) {
    const ChannelLog commands = team_only(first.log.at("SIM_COMMANDS"), team);
    EXPECT_GT(commands.size(), 10u);
    EXPECT_EQ(compare_channel(commands, team_only(second.log.at("SIM_COMMANDS"), team)), "")
        << "on SIM_COMMANDS, team " << team;
  }

  // The comparison can fail: other vision and radio seeds, another game.
  const SslGame other = play(dir, "other", "8", "1");
  ASSERT_EQ(other.status, 0) << other.output;
  EXPECT_NE(compare_channel(first.log.at("RADIO_BLUE"), other.log.at("RADIO_BLUE")), "");
}
