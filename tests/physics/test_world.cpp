// World-level behaviour: determinism, bad input, placement and reset.
#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "physics_test_support.hpp"

namespace ubersim::physics::testing {
namespace {

class WorldTest : public ::testing::TestWithParam<DriveModel> {};

// Encoded sim state: equal bytes means bit-identical.
std::vector<uint8_t> encoded_state(const World& world) {
  sim_state_t state{};
  world.fill_state(state);
  std::vector<uint8_t> bytes(static_cast<std::size_t>(state.getEncodedSize()));
  state.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

// A deterministic stream of packets, as the radio emulator would send them.
sim_commands_t random_packet(std::mt19937& random, const World& world, Team team, double now) {
  std::uniform_real_distribution<double> unit(-1, 1);
  sim_commands_t packet{};
  packet.team = static_cast<int8_t>(team);
  packet.t_received = now;
  packet.t_apply = now + 0.01 + 0.01 * unit(random);
  packet.command_timeout = 0.5;
  for (const auto& r : world.robots()) {
    if (r->team() != team) continue;
    robot_command_t c =
        velocity_command(r->id(), 3 * unit(random), 3 * unit(random), 6 * unit(random));
    c.kick_speed = unit(random) > 0.3 ? 6.0 : 0;
    c.dribbler_speed = unit(random) > 0 ? 500 : 0;
    packet.commands.push_back(c);
  }
  packet.num_commands = static_cast<int32_t>(packet.commands.size());
  return packet;
}

std::vector<std::vector<uint8_t>> run_game(DriveModel model, std::uint64_t seed, double seconds) {
  WorldSetup setup = load_world_setup(kConfigDir, "division_b_6v6", "default");
  setup.robot_types = types_with_model(model);
  setup.seed = seed;
  World world(setup);
  std::mt19937 random(7);
  std::vector<std::vector<uint8_t>> states;
  while (world.time() < seconds) {
    if (world.step_index() % 16 == 0) {
      for (Team team : kTeams) world.submit(random_packet(random, world, team, world.time()));
    }
    world.step();
    states.push_back(encoded_state(world));
  }
  return states;
}

TEST_P(WorldTest, SameSeedAndCommandsGiveBitIdenticalStates) {
  const auto a = run_game(GetParam(), 11, 3.0);
  const auto b = run_game(GetParam(), 11, 3.0);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a[i], b[i]) << "differs at step " << i;
  // The game did move (so the comparison means something).
  EXPECT_NE(a.front(), a.back());
}

TEST_P(WorldTest, ResetReplaysTheSameRun) {
  WorldSetup setup = load_world_setup(kConfigDir, "division_b_6v6", "default");
  setup.robot_types = types_with_model(GetParam());
  World world(setup);
  auto drive = [&] {
    std::mt19937 random(3);
    std::vector<std::vector<uint8_t>> states;
    for (int i = 0; i < 480; ++i) {
      if (i % 16 == 0) {
        for (Team team : kTeams) world.submit(random_packet(random, world, team, world.time()));
      }
      world.step();
      states.push_back(encoded_state(world));
    }
    return states;
  };
  const auto first = drive();
  world.reset();
  EXPECT_EQ(world.step_index(), 0);
  EXPECT_EQ(world.time(), 0.0);
  const auto second = drive();
  EXPECT_EQ(first, second);
}

TEST_P(WorldTest, BadCommandsLeaveTheWorldFinite) {
  World world(empty_world(GetParam()));
  Robot& robot = world.add_robot(Team::Yellow, 0, "omni4_ssl", PlanarState{});
  world.place_ball(robot.type().front_distance + world.setup().ball.radius, 0, 0, 0, 0, 0);
  world.command(Team::Yellow, 0, velocity_command(0, 1.0, 0, 0));
  run_for(world, 0.2);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<robot_command_t> bad;
  for (double v : {nan, inf, -inf}) {
    for (int field = 0; field < 7; ++field) {
      robot_command_t c = velocity_command(0, 0.5, 0, 0);
      double* fields[] = {&c.vx,         &c.vy,         &c.omega,         &c.kick_speed,
                          &c.chip_speed, &c.chip_angle, &c.dribbler_speed};
      *fields[field] = v;
      bad.push_back(c);
    }
  }
  robot_command_t wheels = velocity_command(0, 0, 0, 0);
  wheels.mode = robot_command_t::MODE_WHEEL_SPEEDS;
  wheels.num_wheels = 3;  // the robot has 4
  wheels.wheel_speeds = {1, 2, 3};
  bad.push_back(wheels);
  wheels.num_wheels = 4;
  wheels.wheel_speeds = {nan, 0, 0, 0};
  bad.push_back(wheels);
  robot_command_t bad_mode = velocity_command(0, 1, 0, 0);
  bad_mode.mode = 42;
  bad.push_back(bad_mode);
  for (const auto& c : bad) world.command(Team::Yellow, 0, c);
  EXPECT_EQ(world.counters().commands_dropped, bad.size());
  // Dropped commands leave the last good one in force.
  run_for(world, 0.5);
  EXPECT_NEAR(robot.planar_state().vx, 1.0, 0.1);

  // Huge values are clamped to the robot's limits.
  robot_command_t huge = velocity_command(0, 1e300, -1e300, 1e300);
  huge.kick_speed = 1e300;
  huge.chip_speed = 1e300;
  huge.chip_angle = 1e300;
  huge.dribbler_speed = -1e300;
  world.command(Team::Yellow, 0, huge);
  robot_command_t huge_wheels = wheels;
  huge_wheels.wheel_speeds = {1e300, -1e300, 1e300, -1e300};
  run_for(world, 0.5);
  world.command(Team::Yellow, 0, huge_wheels);
  run_for(world, 0.5);
  const ClampCounts& clamped = world.counters().commands_clamped;
  EXPECT_EQ(clamped.commands, 2u);
  EXPECT_EQ(clamped.text(),
            "2 (speed 1, angular speed 1, wheel speed 1, kick speed 1, chip speed 1, chip angle 1, "
            "dribbler speed 1)");
  // Unknown robots: reported, not fatal.
  world.command(Team::Blue, 0, velocity_command(0, 1, 0, 0));
  world.command(Team::Yellow, 9, velocity_command(9, 1, 0, 0));
  sim_commands_t packet{};
  packet.team = 1;
  packet.t_apply = world.time();
  packet.commands = {velocity_command(3, 1, 0, 0)};
  packet.num_commands = 1;
  world.submit(packet);
  packet.team = 5;  // no such team
  world.submit(packet);
  packet.team = 0;
  packet.t_apply = nan;
  world.submit(packet);
  run_for(world, 0.5);
  EXPECT_EQ(world.counters().commands_unknown_robot, 3u);
  EXPECT_EQ(world.counters().packets_dropped, 2u);

  sim_state_t state{};
  world.fill_state(state);
  for (const auto& r : state.robots) {
    for (double v : {r.x, r.y, r.orientation, r.vx, r.vy, r.omega}) EXPECT_TRUE(std::isfinite(v));
    for (double w : r.wheel_speeds) EXPECT_TRUE(std::isfinite(w));
    EXPECT_LE(std::hypot(r.vx, r.vy), robot.type().max_speed * 1.05);
  }
  for (double v : state.ball.position) EXPECT_TRUE(std::isfinite(v));
  for (double v : state.ball.linear_velocity) EXPECT_TRUE(std::isfinite(v));
  EXPECT_LE(std::hypot(state.ball.linear_velocity[0], state.ball.linear_velocity[1]),
            robot.type().kick_max_speed * 1.05 + robot.type().max_speed);
}

TEST_P(WorldTest, PacketsWaitForTheirApplyTime) {
  World world(empty_world(GetParam()));
  Robot& robot = world.add_robot(Team::Blue, 2, "omni4_ssl", PlanarState{});
  sim_commands_t packet{};
  packet.team = 1;
  packet.t_apply = 0.1;
  packet.commands = {velocity_command(2, 1, 0, 0)};
  packet.num_commands = 1;
  world.submit(packet);
  // Steps starting before 0.1 s leave the robot idle; the one at 0.1 s applies it.
  while (world.time() + 1e-9 < 0.1) {
    world.step();
    EXPECT_LT(robot.last_command_time(), 0);
  }
  world.step();
  EXPECT_NEAR(robot.last_command_time(), 0.1, 1e-9);
}

TEST_P(WorldTest, RobotPlacedOntoTheBallPushesItOut) {
  World world(empty_world(GetParam()));
  world.place_ball(1.0, 1.0, 0, 0, 0, 0);
  sim_control_t place{};
  place.action = sim_control_t::PLACE;
  robot_placement_t p{};
  p.team = 0;
  p.robot_id = 4;
  p.robot_type = "omni4_ssl";
  p.present = true;
  p.x = 1.01;  // the ball ends up just behind its centre
  p.y = 1.0;
  place.robots = {p};
  place.num_robots = 1;
  const PlaceOutcome outcome = world.place(place, false);
  ASSERT_TRUE(outcome.ok) << outcome.message;
  EXPECT_NE(outcome.message.find("ball moved out"), std::string::npos) << outcome.message;
  Robot& robot = *world.robot(Team::Yellow, 4);
  for (int i = 0; i < 240; ++i) {
    world.step();
    const dReal* b = world.ball().position();
    const PlanarState s = robot.planar_state();
    ASSERT_GT(std::hypot(b[0] - s.x, b[1] - s.y), robot.type().front_distance) << "step " << i;
  }
  const dReal* b = world.ball().position();
  EXPECT_LT(b[2], 2 * world.setup().ball.radius);  // on the floor, not on the robot
}

TEST_P(WorldTest, OverlappingRobotsSeparateCalmly) {
  World world(empty_world(GetParam()));
  PlanarState a, b;
  b.x = 0.05;  // 13 cm into each other
  b.y = 0.01;
  Robot& ra = world.add_robot(Team::Yellow, 0, "omni4_ssl", a);
  Robot& rb = world.add_robot(Team::Yellow, 1, "omni4_ssl", b);
  run_for(world, 1.0);
  const PlanarState sa = ra.planar_state(), sb = rb.planar_state();
  EXPECT_GT(std::hypot(sa.x - sb.x, sa.y - sb.y), 2 * ra.type().radius - 0.005);
  EXPECT_LT(std::hypot(sa.vx, sa.vy), 0.2);
  EXPECT_GT(ra.uprightness(), 0.99);
  EXPECT_EQ(world.counters().bodies_reset, 0u);
}

TEST_P(WorldTest, PlacementRequestsAreCheckedBeforeAnythingMoves) {
  World world(empty_world(GetParam()));
  world.add_robot(Team::Yellow, 0, "omni4_ssl", PlanarState{});
  sim_control_t request{};
  robot_placement_t good{};
  good.team = 0;
  good.robot_id = 0;
  good.present = true;
  good.x = 1.0;
  robot_placement_t bad = good;
  bad.robot_id = 1;  // new robot, no type
  request.robots = {good, bad};
  request.num_robots = 2;
  PlaceOutcome outcome = world.place(request, false);
  EXPECT_FALSE(outcome.ok);
  EXPECT_NEAR(world.robot(Team::Yellow, 0)->planar_state().x, 0.0, 1e-9);
  bad.robot_type = "no_such_robot";
  request.robots = {good, bad};
  EXPECT_FALSE(world.place(request, false).ok);
  bad.robot_type = "omni3_cmdragons02";
  bad.x = 100;  // kept inside the walls
  request.robots = {good, bad};
  outcome = world.place(request, false);
  ASSERT_TRUE(outcome.ok) << outcome.message;
  EXPECT_NE(outcome.message.find("inside the walls"), std::string::npos);
  EXPECT_EQ(world.robots().size(), 2u);
  EXPECT_NEAR(world.robot(Team::Yellow, 0)->planar_state().x, 1.0, 1e-9);
  EXPECT_EQ(world.robot(Team::Yellow, 1)->type().name, "omni3_cmdragons02");
  // Remove one; SETUP clears the rest first.
  robot_placement_t gone = good;
  gone.present = false;
  request.robots = {gone};
  request.num_robots = 1;
  EXPECT_TRUE(world.place(request, false).ok);
  EXPECT_EQ(world.robots().size(), 1u);
  request.robots = {};
  request.num_robots = 0;
  EXPECT_TRUE(world.place(request, true).ok);
  EXPECT_TRUE(world.robots().empty());
  // Non-finite values are refused.
  good.robot_type = "omni4_ssl";
  good.x = std::numeric_limits<double>::quiet_NaN();
  request.robots = {good};
  request.num_robots = 1;
  EXPECT_FALSE(world.place(request, false).ok);
}

TEST_P(WorldTest, TippedRobotIsSetUpright) {
  World world(empty_world(GetParam()));
  PlanarState pose;
  pose.x = 1.0;
  pose.heading = 0.5;
  Robot& robot = world.add_robot(Team::Blue, 1, "omni4_ssl", pose);
  // Knock it over: 60 degrees about its x axis.
  dMatrix3 tilted;
  dRFromEulerAngles(tilted, 60 * M_PI / 180, 0, 0.5);
  dBodySetRotation(robot.chassis(), tilted);
  world.step();
  // The jointed robot is caught by the tip check; the planar one cannot tip:
  // its plane-2D joint and re-projection bring it back at once.
  EXPECT_EQ(world.counters().robots_set_upright, GetParam() == DriveModel::Jointed ? 1u : 0u);
  EXPECT_GT(robot.uprightness(), 0.999);
  run_for(world, 0.5);
  EXPECT_GT(robot.uprightness(), 0.99);
  EXPECT_NEAR(robot.planar_state().x, 1.0, 0.05);
}

TEST_P(WorldTest, NonFiniteBodiesAreReset) {
  World world(empty_world(GetParam()));
  PlanarState pose;
  pose.x = -1.0;
  Robot& robot = world.add_robot(Team::Yellow, 2, "omni4_ssl", pose);
  run_for(world, 0.1);
  dBodySetLinearVel(robot.chassis(), std::numeric_limits<double>::quiet_NaN(), 0, 0);
  dBodySetAngularVel(world.ball().body(), 0, std::numeric_limits<double>::infinity(), 0);
  world.step();
  EXPECT_EQ(world.counters().bodies_reset, 2u);
  sim_state_t state{};
  world.fill_state(state);
  for (double v : state.ball.angular_velocity) EXPECT_TRUE(std::isfinite(v));
  EXPECT_NEAR(state.robots[0].x, -1.0, 0.01);
  EXPECT_TRUE(std::isfinite(state.robots[0].vx));
  // A body flung beyond the walls, or exploding, is brought back too.
  dBodySetPosition(world.ball().body(), 50, 0, 0.0215);
  world.step();
  EXPECT_EQ(world.counters().bodies_reset, 3u);
  EXPECT_LT(std::abs(world.ball().position()[0]), world.setup().field.half_length_to_wall());
  dBodySetAngularVel(robot.chassis(), 0, 0, 1e6);
  world.step();
  EXPECT_EQ(world.counters().bodies_reset, 4u);
  EXPECT_LT(std::abs(robot.planar_state().omega), 1.0);
}

INSTANTIATE_TEST_SUITE_P(BothDriveModels, WorldTest,
                         ::testing::Values(DriveModel::Jointed, DriveModel::Planar),
                         drive_model_test_name);

}  // namespace
}  // namespace ubersim::physics::testing
