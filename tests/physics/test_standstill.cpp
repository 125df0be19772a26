// A robot that is told nothing, or told to stop, stays where it is: no creep of
// the wheels' motors, the contacts or the solver over a minute of sim time, for
// every robot type shipped in config/robots (each with the drive model it
// names).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "physics_test_support.hpp"
#include "ubersim/angles.hpp"

namespace ubersim::physics::testing {
namespace {

// What a robot may move in a minute of standing: far below what any camera
// sees (SSL-Vision's noise is about 1 mm and 0.5 deg).
constexpr double kMaxDrift = 0.0005;           // m
constexpr double kMaxTurn = 0.02 * kDegToRad;  // rad
constexpr double kMinute = 60.0;               // s of sim time

std::vector<std::string> shipped_robot_types() {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(kConfigDir + "/robots")) {
    if (entry.path().extension() == ".cfg") names.push_back(entry.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

WorldSetup world_of_shipped_types() {
  WorldSetup setup = empty_world(DriveModel::Jointed);
  setup.robot_types = robot_types_from(kConfigDir);  // each type's own drive model
  return setup;
}

struct Motion {
  double distance = 0;  // m from where it stood
  double turn = 0;      // rad from the heading it had
};

// How far the robot moves over `seconds` from now on.
Motion motion_over(World& world, const Robot& robot, double seconds) {
  const PlanarState start = robot.planar_state();
  run_for(world, seconds);
  const PlanarState end = robot.planar_state();
  return {std::hypot(end.x - start.x, end.y - start.y),
          std::abs(std::remainder(end.heading - start.heading, 2 * M_PI))};
}

class Standstill : public ::testing::TestWithParam<std::string> {};

TEST_P(Standstill, ARobotToldNothingStaysWhereItIs) {
  World world(world_of_shipped_types());
  const Robot& robot = world.add_robot(Team::Yellow, 0, GetParam(), PlanarState{1.0, 0.5, 0.3});
  run_for(world, 0.5);  // settles on its wheels
  const Motion m = motion_over(world, robot, kMinute);
  std::printf("%s, no command: %.3f mm, %.4f deg in %.0f s\n", GetParam().c_str(), m.distance * 1e3,
              m.turn / kDegToRad, kMinute);
  EXPECT_LT(m.distance, kMaxDrift);
  EXPECT_LT(m.turn, kMaxTurn);
}

TEST_P(Standstill, ARobotToldToStopAfterMovingStaysWhereItStopped) {
  World world(world_of_shipped_types());
  const Robot& robot = world.add_robot(Team::Yellow, 0, GetParam(), PlanarState{-1.0, 0, 0});
  world.command(Team::Yellow, 0, velocity_command(0, 1.0, 0, 2.0));
  run_for(world, 1.0);
  world.command(Team::Yellow, 0, velocity_command(0, 0, 0, 0));
  run_for(world, 1.5);  // brakes (at 3 m/s^2 or more: within 0.5 s)
  const Motion m = motion_over(world, robot, kMinute);
  std::printf("%s, stopped: %.3f mm, %.4f deg in %.0f s\n", GetParam().c_str(), m.distance * 1e3,
              m.turn / kDegToRad, kMinute);
  EXPECT_LT(m.distance, kMaxDrift);
  EXPECT_LT(m.turn, kMaxTurn);
}

// The grip is static friction, not a tether: a standing robot pushed by
// another gives way, and afterwards stands where it was pushed to (it takes
// back at most the 3 mm a wheel's grip gives).
TEST(StandstillGrip, ARobotPushedAsideGivesWayAndStandsWhereItWasPushedTo) {
  World world(world_of_shipped_types());
  const Robot& standing = world.add_robot(Team::Yellow, 0, "omni4_ssl", PlanarState{0, 0, 0});
  world.add_robot(Team::Blue, 0, "omni4_ssl", PlanarState{-0.4, 0, 0});
  run_for(world, 0.5);
  world.command(Team::Blue, 0, velocity_command(0, 1.0, 0, 0));
  run_for(world, 1.5);
  world.command(Team::Blue, 0, velocity_command(0, -0.5, 0, 0));  // backs off
  run_for(world, 0.5);
  world.command(Team::Blue, 0, velocity_command(0, 0, 0, 0));
  run_for(world, 0.5);
  const PlanarState pushed = standing.planar_state();
  const Motion after = motion_over(world, standing, 5.0);
  std::printf("pushed %.1f mm, then %.3f mm in 5 s\n", std::hypot(pushed.x, pushed.y) * 1e3,
              after.distance * 1e3);
  EXPECT_GT(pushed.x, 0.05);
  EXPECT_LT(after.distance, 0.0035);
}

std::string type_test_name(const ::testing::TestParamInfo<std::string>& info) {
  return info.param;
}

INSTANTIATE_TEST_SUITE_P(EveryShippedRobotType, Standstill,
                         ::testing::ValuesIn(shipped_robot_types()), type_test_name);

}  // namespace
}  // namespace ubersim::physics::testing
