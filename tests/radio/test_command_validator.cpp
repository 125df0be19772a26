// Bad input from a team's control software: what is dropped, what is cleaned.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "radio_test_util.hpp"
#include "ubersim/radio/command_validator.hpp"

using radio_test::packet;
using ubersim::Team;
using ubersim::radio::Problem;
using ubersim::radio::RobotsOnField;
using ubersim::radio::validate_packet;

namespace {

const ubersim::radio::CommandLimits kLimits{10, 60, 1000, 20, 5000};
const RobotsOnField kRobots{{0, 4}, {1, 4}, {2, 3}};

std::vector<std::int32_t> ids(const ubersim::radio_packet_t& p) {
  std::vector<std::int32_t> out;
  for (const auto& c : p.commands) out.push_back(c.robot_id);
  return out;
}

bool found(const ubersim::radio::Validated& v, Problem problem, std::int32_t robot) {
  for (const auto& f : v.findings)
    if (f.problem == problem && f.robot_id == robot) return true;
  return false;
}

}  // namespace

TEST(CommandValidator, GoodPacketPassesUnchanged) {
  const auto in = packet(0, 9, {0, 1, 2});
  const auto v = validate_packet(in, Team::Yellow, kLimits, kRobots);
  ASSERT_TRUE(v.packet_ok);
  EXPECT_TRUE(v.findings.empty());
  EXPECT_EQ(ids(v.packet), (std::vector<std::int32_t>{0, 1, 2}));
  EXPECT_EQ(v.packet.sequence, 9);
  EXPECT_EQ(v.packet.num_commands, 3);
  EXPECT_EQ(v.packet.commands[1].vx, in.commands[1].vx);
}

TEST(CommandValidator, UnknownTeamDropsThePacket) {
  auto in = packet(7, 1, {0});
  const auto v = validate_packet(in, Team::Yellow, kLimits, kRobots);
  EXPECT_FALSE(v.packet_ok);
  EXPECT_TRUE(found(v, Problem::UnknownTeam, -1));
}

TEST(CommandValidator, TeamFieldNotMatchingTheChannelDropsThePacket) {
  const auto v = validate_packet(packet(1, 1, {0}), Team::Yellow, kLimits, kRobots);
  EXPECT_FALSE(v.packet_ok);
  EXPECT_TRUE(found(v, Problem::TeamMismatch, -1));
}

TEST(CommandValidator, NonFiniteValuesDropThatRobotsEntry) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  auto in = packet(0, 1, {0, 1, 2});
  in.commands[0].vy = nan;
  in.commands[2].dribbler_speed = -inf;
  const auto v = validate_packet(in, Team::Yellow, kLimits, kRobots);
  ASSERT_TRUE(v.packet_ok);
  EXPECT_EQ(ids(v.packet), (std::vector<std::int32_t>{1}));
  EXPECT_TRUE(found(v, Problem::NonFinite, 0));
  EXPECT_TRUE(found(v, Problem::NonFinite, 2));
}

TEST(CommandValidator, AbsurdValuesDropThatRobotsEntry) {
  struct Case {
    const char* what;
    void (*spoil)(ubersim::robot_command_t&);
  };
  const Case cases[] = {
      {"speed in mm/s", [](ubersim::robot_command_t& c) { c.vx = 1500; }},
      {"diagonal speed", [](ubersim::robot_command_t& c) { c.vx = c.vy = 7.5; }},  // 10.6 m/s
      {"spin", [](ubersim::robot_command_t& c) { c.omega = -100; }},
      {"kick", [](ubersim::robot_command_t& c) { c.kick_speed = 65; }},
      {"negative kick", [](ubersim::robot_command_t& c) { c.kick_speed = -1; }},
      {"chip", [](ubersim::robot_command_t& c) { c.chip_speed = 21; }},
      {"chip angle", [](ubersim::robot_command_t& c) { c.chip_angle = 2.0; }},
      {"dribbler", [](ubersim::robot_command_t& c) { c.dribbler_speed = -6000; }},
  };
  for (const auto& test_case : cases) {
    auto in = packet(0, 1, {0, 1});
    test_case.spoil(in.commands[1]);
    const auto v = validate_packet(in, Team::Yellow, kLimits, kRobots);
    ASSERT_TRUE(v.packet_ok) << test_case.what;
    EXPECT_EQ(ids(v.packet), (std::vector<std::int32_t>{0})) << test_case.what;
    EXPECT_TRUE(found(v, Problem::AbsurdValue, 1)) << test_case.what;
  }
}

TEST(CommandValidator, ValuesAtTheLimitsPass) {
  auto in = packet(0, 1, {0});
  in.commands[0].vx = 6;
  in.commands[0].vy = 8;  // exactly 10 m/s
  in.commands[0].omega = -60;
  in.commands[0].kick_speed = 20;
  in.commands[0].dribbler_speed = -5000;
  EXPECT_TRUE(validate_packet(in, Team::Yellow, kLimits, kRobots).findings.empty());
}

TEST(CommandValidator, DuplicateRobotIdsDropEveryEntryOfThatRobot) {
  auto in = packet(1, 1, {0, 1, 0, 2});
  const auto v = validate_packet(in, Team::Blue, kLimits, kRobots);
  ASSERT_TRUE(v.packet_ok);
  EXPECT_EQ(ids(v.packet), (std::vector<std::int32_t>{1, 2}));
  EXPECT_TRUE(found(v, Problem::DuplicateRobot, 0));
  EXPECT_EQ(v.findings.size(), 1u);  // reported once per robot, not per entry
}

TEST(CommandValidator, RobotsNotOnTheFieldAreReportedAndLeftOut) {
  const auto v = validate_packet(packet(0, 1, {0, 42, -3}), Team::Yellow, kLimits, kRobots);
  ASSERT_TRUE(v.packet_ok);
  EXPECT_EQ(ids(v.packet), (std::vector<std::int32_t>{0}));
  EXPECT_TRUE(found(v, Problem::OffField, 42));
  EXPECT_TRUE(found(v, Problem::OffField, -3));
}

TEST(CommandValidator, UnknownModeDropsTheEntry) {
  auto in = packet(0, 1, {0, 1});
  in.commands[0].mode = 9;
  const auto v = validate_packet(in, Team::Yellow, kLimits, kRobots);
  EXPECT_EQ(ids(v.packet), (std::vector<std::int32_t>{1}));
  EXPECT_TRUE(found(v, Problem::UnknownMode, 0));
}

TEST(CommandValidator, WheelSpeedModeNeedsTheRobotsWheelCount) {
  auto in = packet(0, 1, {0, 1, 2});
  for (auto& c : in.commands) {
    c.mode = ubersim::robot_command_t::MODE_WHEEL_SPEEDS;
    c.wheel_speeds.assign(4, 20.0);
    c.num_wheels = 4;
  }
  in.commands[1].wheel_speeds[3] = 2000;                               // absurd
  const auto v = validate_packet(in, Team::Yellow, kLimits, kRobots);  // robot 2 has 3 wheels
  EXPECT_EQ(ids(v.packet), (std::vector<std::int32_t>{0}));
  EXPECT_TRUE(found(v, Problem::AbsurdValue, 1));
  EXPECT_TRUE(found(v, Problem::WheelCount, 2));
  EXPECT_EQ(v.packet.commands[0].wheel_speeds, (std::vector<double>(4, 20.0)));
}

TEST(CommandValidator, VelocityModeEntriesLoseTheirUnusedWheelSpeeds) {
  auto in = packet(0, 1, {0});
  in.commands[0].wheel_speeds = {std::nan(""), 1e9};
  in.commands[0].num_wheels = 2;
  const auto v = validate_packet(in, Team::Yellow, kLimits, kRobots);
  ASSERT_EQ(v.packet.commands.size(), 1u);
  EXPECT_EQ(v.packet.commands[0].num_wheels, 0);
  EXPECT_TRUE(v.packet.commands[0].wheel_speeds.empty());
}

// The Python module's check: the same rules without the profile's sanity
// limits, which an emulated radio applies later (or physics clamps).
TEST(CommandValidator, WithoutSanityLimitsOnlyWhatNoRobotCanApplyIsFound) {
  auto in = packet(0, 1, {0, 1, 2});
  in.commands[0].vx = 1e9;         // far beyond LIMIT_SPEED: physics clamps it
  in.commands[0].kick_speed = -1;  // negative: physics ignores the kick
  in.commands[1].omega = std::nan("");
  in.commands[2].mode = ubersim::robot_command_t::MODE_WHEEL_SPEEDS;
  in.commands[2].wheel_speeds = {1, 2, 3, 4};
  in.commands[2].num_wheels = 4;  // robot 2 has 3 wheels
  const auto v = validate_packet(in, Team::Yellow, kRobots);
  EXPECT_EQ(ids(v.packet), (std::vector<std::int32_t>{0}));
  EXPECT_EQ(v.findings.size(), 2u);
  EXPECT_TRUE(found(v, Problem::NonFinite, 1));
  EXPECT_TRUE(found(v, Problem::WheelCount, 2));
  EXPECT_FALSE(validate_packet(in, Team::Yellow, kLimits, kRobots).findings.size() == 2u)
      << "with the limits, robot 0's entry is absurd too";
}
