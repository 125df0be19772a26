// The emulator without transport: both teams, clock, feedback, reports.
#include <gtest/gtest.h>

#include <cmath>

#include "radio_test_util.hpp"
#include "ubersim/radio/radio_emulator.hpp"

using radio_test::packet;
using radio_test::profile;
using radio_test::state;
using ubersim::Team;
using ubersim::radio::Problem;
using ubersim::radio::RadioEmulator;

namespace {

constexpr double kStep = 1.0 / 240;
// The wall time the core is handed (it reads no clock): one instant, unless a
// test says otherwise.
const RadioEmulator::Clock::time_point kWall{};

struct Recorder {
  std::vector<ubersim::sim_commands_t> commands;
  std::vector<std::pair<Team, ubersim::radio_feedback_t>> feedback;
  // Everything the emulator returns, in order.
  void add(RadioEmulator::Output o) {
    for (auto& m : o.commands) commands.push_back(std::move(m));
    for (auto& f : o.feedback) feedback.push_back(std::move(f));
  }
};

}  // namespace

// Paced (speed 1): a packet arrives at the last state's sim time plus the
// whole steps of wall time since that state, by the wall times the core is
// handed (it reads no clock, so the stamps do not depend on when the test runs).
TEST(RadioEmulatorCore, PacedPacketsArriveByTheWallTimeHandedIn) {
  using namespace std::chrono_literals;
  Recorder out;
  RadioEmulator emulator({profile(0, 0.0), profile(0, 0.0)}, std::nullopt);
  auto paced = state(1.0, 240, 1);
  paced.speed_factor = 1;
  out.add(emulator.on_sim_state(paced, kWall));
  out.add(emulator.on_radio_packet(Team::Yellow, packet(0, 1, {0}), kWall + 10ms));
  out.add(emulator.on_radio_packet(Team::Blue, packet(1, 1, {0}), kWall + 5s));
  ASSERT_EQ(out.commands.size(), 2u);
  EXPECT_NEAR(out.commands[0].t_apply, 1.0 + 2 * kStep, 1e-9);  // 10 ms: two whole steps
  EXPECT_NEAR(out.commands[1].t_apply, 1.1, 1e-9);  // at most 0.1 s: physics stopped or fell behind
}

TEST(RadioEmulatorCore, PacketsBeforeAnySimStateAreDroppedAndCounted) {
  Recorder out;
  RadioEmulator emulator({profile(60, 0.03), profile(60, 0.03)}, std::nullopt);
  out.add(emulator.on_radio_packet(Team::Yellow, packet(0, 1, {0}), kWall));
  EXPECT_TRUE(out.commands.empty());
  EXPECT_EQ(emulator.report(Team::Yellow).problem(Problem::NoSimTime), 1u);
  out.add(emulator.on_sim_state(state(0.5, 120, 3), kWall));
  out.add(emulator.on_radio_packet(Team::Yellow, packet(0, 2, {0}), kWall));
  ASSERT_EQ(out.commands.size(), 1u);
  EXPECT_DOUBLE_EQ(out.commands[0].t_received, 0.5);  // the latest SIM_STATE's time
}

TEST(RadioEmulatorCore, EachTeamHasItsOwnLinkAndTimeout) {
  Recorder out;
  auto yellow = profile(10, 0.05);
  yellow.command_timeout = 0.4;
  auto blue = profile(0, 0.0);
  blue.command_timeout = 0.1;
  RadioEmulator emulator({yellow, blue}, std::nullopt);
  out.add(emulator.on_sim_state(state(1.0, 240, 2), kWall));
  out.add(emulator.on_radio_packet(Team::Yellow, packet(0, 1, {0}), kWall));
  out.add(
      emulator.on_radio_packet(Team::Yellow, packet(0, 2, {0}), kWall));  // yellow link busy: waits
  out.add(
      emulator.on_radio_packet(Team::Blue, packet(1, 1, {0}), kWall));  // blue's link is its own
  out.add(emulator.on_radio_packet(Team::Blue, packet(1, 2, {0}), kWall));
  ASSERT_EQ(out.commands.size(), 3u);
  EXPECT_EQ(out.commands[0].team, 0);
  EXPECT_DOUBLE_EQ(out.commands[0].command_timeout, 0.4);
  EXPECT_NEAR(out.commands[0].t_apply, 1.05, 1e-9);
  EXPECT_EQ(out.commands[1].team, 1);
  EXPECT_DOUBLE_EQ(out.commands[1].command_timeout, 0.1);
  EXPECT_DOUBLE_EQ(out.commands[1].t_apply, 1.0);
  EXPECT_EQ(out.commands[2].sequence, 2);
  // The waiting yellow packet goes out on the SIM_STATE at which its link is free.
  out.add(emulator.on_sim_state(state(1.05, 252, 2), kWall));
  EXPECT_EQ(out.commands.size(), 3u);
  out.add(emulator.on_sim_state(state(1.1, 264, 2), kWall));
  ASSERT_EQ(out.commands.size(), 4u);
  EXPECT_EQ(out.commands[3].team, 0);
  EXPECT_EQ(out.commands[3].sequence, 2);
}

TEST(RadioEmulatorCore, RobotsNotOnTheFieldAreCountedPerTeam) {
  Recorder out;
  RadioEmulator emulator({profile(0, 0), profile(0, 0)}, std::nullopt);
  out.add(emulator.on_sim_state(state(1.0, 240, 3), kWall));  // robots 0..2 of each team
  out.add(emulator.on_radio_packet(Team::Blue, packet(1, 1, {0, 3, 11}), kWall));
  ASSERT_EQ(out.commands.size(), 1u);
  EXPECT_EQ(out.commands[0].num_commands, 1);
  EXPECT_EQ(emulator.report(Team::Blue).problem(Problem::OffField), 2u);
  EXPECT_EQ(emulator.report(Team::Yellow).problem(Problem::OffField), 0u);
  EXPECT_NE(emulator.summary(Team::Blue).find("robot not on the field: 2"), std::string::npos)
      << emulator.summary(Team::Blue);
}

TEST(RadioEmulatorCore, FeedbackArrivesWithItsLatencyAndTheMeasuredState) {
  Recorder out;
  auto yellow = profile(60, 0.03);  // feedback 30 Hz, 20 ms, no loss
  RadioEmulator emulator({yellow, profile(60, 0.03)}, std::nullopt);
  const int steps = 240 * 10;
  for (int k = 0; k < steps; ++k) {
    auto s = state(k * kStep, k, 2);
    for (auto& r : s.robots) {
      r.ball_contact = (k / 7 + r.robot_id) % 2 == 0;
      r.kicker_charged = (k / 13 + r.robot_id) % 3 != 0;
    }
    out.add(emulator.on_sim_state(s, kWall));
  }
  std::size_t yellow_count = 0;
  for (const auto& [team, fb] : out.feedback) {
    EXPECT_EQ(fb.team, static_cast<int>(team));
    if (team != Team::Yellow) continue;
    ++yellow_count;
    const double delay = fb.t_sent - fb.t_measured;
    EXPECT_GE(delay, 0.02 - 1e-9);
    EXPECT_LT(delay, 0.02 + kStep);
    const long k = std::lround(fb.t_measured / kStep);
    ASSERT_EQ(fb.num_robots, 2);
    for (const auto& r : fb.robots) {
      EXPECT_EQ(r.ball_contact, (k / 7 + r.robot_id) % 2 == 0);
      EXPECT_EQ(r.kicker_charged, (k / 13 + r.robot_id) % 3 != 0);
    }
  }
  // 30 Hz over 10 s, less what is still in flight at the end.
  EXPECT_NEAR(static_cast<double>(yellow_count), 300, 1);
}

TEST(RadioEmulatorCore, AResetStartsTheLinksAfresh) {
  Recorder out;
  RadioEmulator emulator({profile(1, 0.1), profile(1, 0.1)}, std::nullopt);
  out.add(emulator.on_sim_state(state(30.0, 7200, 1), kWall));
  out.add(emulator.on_radio_packet(Team::Yellow, packet(0, 1, {0}), kWall));
  out.add(
      emulator.on_radio_packet(Team::Yellow, packet(0, 2, {0}), kWall));  // waits for the busy link
  out.add(emulator.on_sim_state(state(0.0, 0, 1), kWall));                // world reset
  EXPECT_EQ(emulator.resets(), 1u);
  out.add(emulator.on_sim_state(state(2.0, 480, 1), kWall));  // the old waiting packet is gone
  ASSERT_EQ(out.commands.size(), 1u);
  out.add(emulator.on_radio_packet(Team::Yellow, packet(0, 3, {0}), kWall));
  ASSERT_EQ(out.commands.size(), 2u);
  EXPECT_NEAR(out.commands[1].t_apply, 2.1, 1e-9);
}

TEST(RadioEmulatorCore, OutOfOrderSimStatesAreIgnored) {
  Recorder out;
  RadioEmulator emulator({profile(0, 0), profile(0, 0)}, std::nullopt);
  out.add(emulator.on_sim_state(state(10.0, 2400, 1), kWall));
  out.add(emulator.on_sim_state(state(9.0, 2160, 1), kWall));  // stale
  auto bad = state(std::nan(""), 2401, 1);
  out.add(emulator.on_sim_state(bad, kWall));
  EXPECT_EQ(emulator.rejected_sim_states(), 2u);
  out.add(emulator.on_radio_packet(Team::Yellow, packet(0, 1, {0}), kWall));
  ASSERT_EQ(out.commands.size(), 1u);
  EXPECT_DOUBLE_EQ(out.commands[0].t_received, 10.0);
}

TEST(RadioEmulatorCore, SeedOverrideMakesRunsRepeatable) {
  const auto run = [](std::uint64_t seed) {
    Recorder out;
    RadioEmulator emulator({profile(0, 0.03, 0.01, 0.3, 0.3), profile(0, 0.03, 0.01, 0.3, 0.3)},
                           seed);
    for (int k = 0; k < 200; ++k) {
      out.add(emulator.on_sim_state(state(k * kStep, k, 3), kWall));
      out.add(emulator.on_radio_packet(Team::Yellow, packet(0, k, {0, 1, 2}), kWall));
    }
    std::vector<double> trace;
    for (const auto& c : out.commands) trace.push_back(c.t_apply + 10.0 * c.num_commands);
    return trace;
  };
  EXPECT_EQ(run(1), run(1));
  EXPECT_NE(run(1), run(2));
}
