// Unchanged LCM team programs in sync mode (docs/timeshim.md, "Team programs
// that speak LCM"): tools/launch.sh --sync --team yellow 'lcm:COMMAND' --team
// blue 'lcm:COMMAND' starts two demo teams WITHOUT --sync (they know nothing
// of sync mode: they act on each VISION frame at their own rate and stamp
// their packets with the capture time) under the time shim in the SSL
// bridge, each on a private LCM bus the bridge relays. Checked: no team
// dropped; each command is stamped with the sim time the team sent it (the
// publication of the frame it acted on, not its capture time); two runs, the
// second beside a CPU hog, record the same bytes.
// ISOLATED: own network namespace, so the league's ports are free.
#include <gtest/gtest.h>

#include <map>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/vision_schedule_t.hpp>

#include "timed_game.hpp"

using namespace e2e;

namespace {

std::string demo_team(const std::string& colour) {
  return std::string("lcm:") + UBERSIM_BIN_DIR + "/ubersim_demo_team --team " + colour;
}

// One game of 5 s of sim time, seed 7: a demo team on each side.
TimedGame play(const TempDir& dir, const std::string& name, bool hog) {
  return play_timed_game(dir, name, demo_team("yellow"), demo_team("blue"), "5", "7", hog);
}

// Every command packet was sent when the team had just been handed a frame:
// its t_sent is the sim time the bridge handed the team a step's frames (the
// step's t_state in SIM_VISION_SCHEDULE), later than the capture time the
// demo team itself writes into it.
void check_team(const TimedGame& game, const std::string& channel) {
  SCOPED_TRACE(channel);
  std::map<double, double> capture_of;  // handed at -> the latest capture handed then (s)
  for (const auto& step :
       decode_all<ubersim::vision_schedule_t>(game.log.at("SIM_VISION_SCHEDULE"))) {
    for (double capture : step.t_capture) capture_of[step.t_state] = capture;
  }
  double last = -1;
  std::size_t with_commands = 0;
  for (const auto& packet : decode_all<ubersim::radio_packet_t>(game.log.at(channel))) {
    ASSERT_GE(packet.t_sent, last) << "t_sent never goes back";
    last = packet.t_sent;
    if (packet.num_commands == 0) continue;  // a promise: nothing sent before t_sent
    ++with_commands;
    // The group's clock counts whole nanoseconds.
    const auto frame = capture_of.lower_bound(packet.t_sent - 1e-9);
    ASSERT_TRUE(frame != capture_of.end() && frame->first <= packet.t_sent + 1e-9)
        << "a command sent at " << packet.t_sent << " s: no frame was handed to the team then";
    EXPECT_LT(frame->second, packet.t_sent - 1e-6)
        << "a command stamped " << packet.t_sent << " s, its frame's capture time";
  }
  EXPECT_GT(with_commands, 100u) << "5 s of a 30 Hz team";
}

}  // namespace

TEST(LcmTimedTeams, UnchangedLcmTeamsPlayAReproducibleSyncGameUnderTheTimeShim) {
  TempDir dir;
  const TimedGame first = play(dir, "first", false);
  ASSERT_EQ(first.status, 0) << first.output << first.bridge_log << first.radio_log;
  EXPECT_NE(first.radio_log.find("sync: no client was dropped"), std::string::npos)
      << first.radio_log;
  EXPECT_NE(first.radio_log.find("0 duplicated or out of order; 0 client timeouts"),
            std::string::npos)
      << first.radio_log;
  EXPECT_NE(first.bridge_log.find("yellow radio packets relayed="), std::string::npos)
      << first.bridge_log;
  check_team(first, "RADIO_YELLOW");
  check_team(first, "RADIO_BLUE");

  const TimedGame second = play(dir, "second", true);
  ASSERT_EQ(second.status, 0) << second.output << second.bridge_log << second.radio_log;
  for (const std::string& channel : reproducible_channels()) {
    ASSERT_TRUE(first.log.count(channel)) << channel << " was not recorded";
    ASSERT_TRUE(second.log.count(channel)) << channel << " was not recorded";
    EXPECT_GT(first.log.at(channel).size(), 10u) << channel;
    EXPECT_EQ(compare_channel(first.log.at(channel), second.log.at(channel)), "")
        << "on " << channel;
  }
}
