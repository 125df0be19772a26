// Unchanged team programs in sync mode (docs/timeshim.md, "Integration with
// sync mode"): tools/launch.sh --sync --team yellow 'COMMAND' --team blue
// 'COMMAND' starts two SSL team programs that know nothing of ubersim (a C++
// one, ssl_timed_team, and a Python one, ssl_timed_team.py: threads, a 50 Hz
// sleep loop, socket timeouts, poll/select, a child process, wall-clock reads)
// under the time shim in the SSL bridge. Checked: no team dropped; each
// command is stamped with the sim time the team sent it (its own loop's
// times, multiples of 20 ms, not frame capture times); the team's own clock
// is sim time; two runs, the second beside a CPU hog, record the same bytes.
// ISOLATED: own network namespace, so the league's ports are free.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <regex>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/sim_control_ack_t.hpp>
#include <ubersim/sim_control_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <ubersim/vision_schedule_t.hpp>

#include "timed_game.hpp"

using namespace e2e;

namespace {

constexpr const char* kPython = "/usr/bin/python3";

// The C++ team yellow and the Python team blue on the SSL protocols, 4 s.
TimedGame play(const TempDir& dir, const std::string& name, const std::string& seed, bool hog) {
  return play_timed_game(dir, name, std::string(UBERSIM_SSL_TIMED_TEAM_EXE) + " --team yellow",
                         std::string(kPython) + " " + UBERSIM_SSL_TIMED_TEAM_PY + " --team blue",
                         "4", seed, hog);
}

// The C++ team playing both colours on grSim's protocol, 3 s.
TimedGame play_grsim(const TempDir& dir, const std::string& name, const std::string& seed,
                     bool hog) {
  const std::string team = std::string("grsim:") + UBERSIM_SSL_TIMED_TEAM_EXE + " --protocol grsim";
  return play_timed_game(dir, name, team + " --team yellow", team + " --team blue", "3", seed, hog);
}

// The times a team's loop printed ("loop N steady|monotonic S ...").
std::vector<double> loop_times(const std::string& team_log) {
  static const std::regex line(R"(loop (\d+) (steady|monotonic) ([0-9.]+) (wall|time) ([0-9.]+))");
  std::vector<double> times;
  for (auto it = std::sregex_iterator(team_log.begin(), team_log.end(), line);
       it != std::sregex_iterator(); ++it) {
    const double t = std::stod((*it)[3]);
    EXPECT_NEAR(std::stod((*it)[5]), 1767225600.0 + t, 1e-5) << "its wall clock is sim time too";
    times.push_back(t);
  }
  return times;
}

bool on_grid(double t) {
  return std::fabs(t / 0.02 - std::round(t / 0.02)) < 1e-6;
}

void check_team(const TimedGame& game, const std::string& channel, const std::string& team_log,
                std::size_t min_loops = 150) {
  SCOPED_TRACE(channel);
  const auto packets = decode_all<ubersim::radio_packet_t>(game.log.at(channel));
  const auto states = decode_all<ubersim::sim_state_t>(game.log.at("SIM_STATE"));
  ASSERT_FALSE(states.empty());
  double last = -1;
  std::size_t with_commands = 0;
  for (const auto& packet : packets) {
    ASSERT_GE(packet.t_sent, last) << "t_sent never goes back";
    last = packet.t_sent;
    if (packet.num_commands == 0) continue;  // a promise: nothing sent before t_sent
    ++with_commands;
    EXPECT_TRUE(on_grid(packet.t_sent))
        << "a command sent at " << packet.t_sent << " s: not a time of the team's 50 Hz loop";
  }
  // The team's loop ran on sim time: loop N at N * 20 ms, up to where physics stopped.
  const std::vector<double> loops = loop_times(team_log);
  ASSERT_GT(loops.size(), min_loops) << team_log;
  for (std::size_t i = 0; i < loops.size(); ++i) {
    ASSERT_NEAR(loops[i], 0.02 * static_cast<double>(i), 1e-6) << "loop " << i;
  }
  EXPECT_NEAR(loops.back(), states.back().sim_time, 0.25);
  EXPECT_GT(with_commands, min_loops);
}

// The step of the first state at or after sim time t with vision frames (the
// vision emulator's schedule lists them), -1 if none.
std::int64_t first_frame_step_from(const TimedGame& game, double t) {
  for (const auto& schedule :
       decode_all<ubersim::vision_schedule_t>(game.log.at("SIM_VISION_SCHEDULE"))) {
    if (schedule.num_frames > 0 && schedule.t_state >= t - 1e-9) return schedule.step;
  }
  return -1;
}

// The C++ yellow team teleported the ball once during the game (its loop 41,
// 0.82 s): the bridge passed it on to physics, which applied it at the state
// of the next frame (where physics waits), not at the capture instant's state
// without a frame in between (which physics runs past while the command
// travels).
void expect_teleport(const TimedGame& game) {
  ASSERT_TRUE(game.log.count("SIM_CONTROL"));
  ASSERT_TRUE(game.log.count("SIM_CONTROL_ACK"));
  std::vector<std::int64_t> teleports;
  for (const auto& request : decode_all<ubersim::sim_control_t>(game.log.at("SIM_CONTROL"))) {
    if (request.sender == "ubersim_ssl_bridge" && request.has_ball &&
        std::fabs(request.ball.position[0] - 0.5) < 1e-6) {
      teleports.push_back(request.request_id);
    }
  }
  ASSERT_EQ(teleports.size(), 1U) << game.bridge_log;
  constexpr double kSent = 0.82;  // loop 41 of the 50 Hz loop
  const std::int64_t frame_step = first_frame_step_from(game, kSent);
  int acknowledged = 0;
  for (const auto& ack : decode_all<ubersim::sim_control_ack_t>(game.log.at("SIM_CONTROL_ACK"))) {
    if (ack.sender != "ubersim_ssl_bridge" || ack.request_id != teleports.front()) continue;
    ++acknowledged;
    EXPECT_TRUE(ack.ok) << ack.message;
    EXPECT_EQ(ack.step, frame_step) << "applied at sim time " << ack.sim_time;
  }
  EXPECT_EQ(acknowledged, 1);
}

void expect_no_drop(const TimedGame& game) {
  EXPECT_NE(game.radio_log.find("sync: no client was dropped"), std::string::npos)
      << game.radio_log;
  EXPECT_NE(game.radio_log.find("0 duplicated or out of order; 0 client timeouts"),
            std::string::npos)
      << game.radio_log;
}

void expect_same_bytes(const TimedGame& first, const TimedGame& second) {
  for (const std::string& channel : reproducible_channels()) {
    ASSERT_TRUE(first.log.count(channel)) << channel << " was not recorded";
    ASSERT_TRUE(second.log.count(channel)) << channel << " was not recorded";
    EXPECT_EQ(compare_channel(first.log.at(channel), second.log.at(channel)), "")
        << "on " << channel;
  }
  EXPECT_EQ(first.yellow_log, second.yellow_log);
  EXPECT_EQ(first.blue_log, second.blue_log);
}

}  // namespace

TEST(TimedTeams, UnchangedTeamsPlayAReproducibleSyncGameUnderTheTimeShim) {
  if (access(kPython, X_OK) != 0) GTEST_SKIP() << kPython << " not found: the Python team needs it";
  TempDir dir;
  const TimedGame first = play(dir, "first", "7", false);
  ASSERT_EQ(first.status, 0) << first.output << first.bridge_log << first.radio_log;
  expect_no_drop(first);
  check_team(first, "RADIO_YELLOW", first.yellow_log);
  check_team(first, "RADIO_BLUE", first.blue_log);
  expect_teleport(first);

  // The teleport too is applied at the same sim time: SIM_STATE is the same.
  const TimedGame second = play(dir, "second", "7", true);
  ASSERT_EQ(second.status, 0) << second.output << second.bridge_log << second.radio_log;
  expect_same_bytes(first, second);
}

// The same C++ team speaking grSim's protocol (grSim_Packet to 20011), both
// colours: its commands are read at the group's quiescences and stamped with
// the time its loop sent them, like RobotControl.
TEST(TimedTeams, GrsimProtocolTeamsPlayAReproducibleSyncGameUnderTheTimeShim) {
  TempDir dir;
  const TimedGame first = play_grsim(dir, "first", "7", false);
  ASSERT_EQ(first.status, 0) << first.output << first.bridge_log << first.radio_log;
  expect_no_drop(first);
  check_team(first, "RADIO_YELLOW", first.yellow_log, 100);
  check_team(first, "RADIO_BLUE", first.blue_log, 100);
  for (const std::string colour : {"yellow", "blue"}) {
    EXPECT_NE(first.bridge_log.find("grSim radio packets " + colour + " (timed)="),
              std::string::npos)
        << first.bridge_log;
  }
  EXPECT_EQ(first.bridge_log.find("grSim command packets dropped"), std::string::npos)
      << first.bridge_log;

  const TimedGame second = play_grsim(dir, "second", "7", true);
  ASSERT_EQ(second.status, 0) << second.output << second.bridge_log << second.radio_log;
  expect_same_bytes(first, second);
}
