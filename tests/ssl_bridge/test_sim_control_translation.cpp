// SimulatorCommand -> SIM_CONTROL requests and errors, in-process.
#include <gtest/gtest.h>
#include <ssl_simulation_custom_erforce_realism.pb.h>

#include <cmath>
#include <ubersim/team_t.hpp>

#include "ubersim/ssl_bridge/sim_control_translation.hpp"

using namespace ubersim;
using namespace ubersim::ssl;

namespace {

sim_state_t state_with_robot(int8_t team, int32_t id, double x, double y, double heading) {
  sim_state_t state{};
  robot_state_t robot{};
  robot.team = team;
  robot.robot_id = id;
  robot.x = x;
  robot.y = y;
  robot.orientation = heading;
  state.robots.push_back(robot);
  state.num_robots = 1;
  state.ball.position[0] = 0.25;
  state.ball.position[1] = -0.5;
  return state;
}

bool has_code(const Errors& errors, const std::string& code) {
  for (const auto& e : errors) {
    if (e.code() == code) return true;
  }
  return false;
}

}  // namespace

TEST(SslSimControl, TeleportBallWithVelocityIsOnePlace) {
  SimulatorCommand command;
  TeleportBall* ball = command.mutable_control()->mutable_teleport_ball();
  ball->set_x(1.5f);
  ball->set_y(-2.25f);
  ball->set_vx(0.5f);
  ball->set_vy(-1.0f);
  const auto out = translate_simulator_command(command, nullptr, {});
  EXPECT_TRUE(out.errors.empty());
  ASSERT_EQ(out.requests.size(), 1u);
  const sim_control_t& place = out.requests[0];
  EXPECT_EQ(place.action, +sim_control_t::PLACE);
  EXPECT_TRUE(place.has_ball);
  EXPECT_EQ(place.num_robots, 0);
  EXPECT_DOUBLE_EQ(place.ball.position[0], 1.5);
  EXPECT_DOUBLE_EQ(place.ball.position[1], -2.25);
  EXPECT_DOUBLE_EQ(place.ball.position[2], 0.0);
  EXPECT_DOUBLE_EQ(place.ball.linear_velocity[0], 0.5);
  EXPECT_DOUBLE_EQ(place.ball.linear_velocity[1], -1.0);
}

TEST(SslSimControl, UnsetBallCoordinateKeepsTheCurrentOne) {
  const sim_state_t state = state_with_robot(team_t::BLUE, 0, 3, 3, 0);
  SimulatorCommand command;
  command.mutable_control()->mutable_teleport_ball()->set_x(1.0f);
  const auto out = translate_simulator_command(command, &state, {});
  ASSERT_EQ(out.requests.size(), 1u);
  EXPECT_DOUBLE_EQ(out.requests[0].ball.position[0], 1.0);
  EXPECT_DOUBLE_EQ(out.requests[0].ball.position[1], -0.5);
  // Without any state the missing y cannot be filled in: an error, no request.
  const auto blind = translate_simulator_command(command, nullptr, {});
  EXPECT_TRUE(blind.requests.empty());
  EXPECT_TRUE(has_code(blind.errors, kErrorInvalid));
}

TEST(SslSimControl, ByForceMovesByForceAnEmptyTeleportEndsItNaNIsAnError) {
  const sim_state_t state = state_with_robot(team_t::BLUE, 3, 1.0, 2.0, 0.5);
  SimulatorCommand command;
  TeleportBall* ball = command.mutable_control()->mutable_teleport_ball();
  ball->set_x(1);
  ball->set_by_force(true);
  TeleportRobot* robot = command.mutable_control()->add_teleport_robot();
  robot->mutable_id()->set_id(3);
  robot->mutable_id()->set_team(BLUE);
  robot->set_y(-1);
  robot->set_by_force(true);
  auto out = translate_simulator_command(command, &state, {});
  EXPECT_TRUE(out.errors.empty());
  ASSERT_EQ(out.requests.size(), 1u);
  EXPECT_EQ(out.requests[0].ball.mode, +ball_placement_t::BY_FORCE);
  EXPECT_DOUBLE_EQ(out.requests[0].ball.position[0], 1.0);
  EXPECT_DOUBLE_EQ(out.requests[0].ball.position[1], -0.5);  // unset: where it is
  ASSERT_EQ(out.requests[0].num_robots, 1);
  EXPECT_EQ(out.requests[0].robots[0].mode, +ball_placement_t::BY_FORCE);
  EXPECT_DOUBLE_EQ(out.requests[0].robots[0].x, 1.0);
  EXPECT_DOUBLE_EQ(out.requests[0].robots[0].y, -1.0);
  EXPECT_DOUBLE_EQ(out.requests[0].robots[0].orientation, 0.5);

  SimulatorCommand end;
  end.mutable_control()->mutable_teleport_ball()->set_by_force(false);
  TeleportRobot* stop = end.mutable_control()->add_teleport_robot();
  stop->mutable_id()->set_id(3);
  stop->mutable_id()->set_team(BLUE);
  out = translate_simulator_command(end, &state, {});
  EXPECT_TRUE(out.errors.empty());
  ASSERT_EQ(out.requests.size(), 1u);
  EXPECT_EQ(out.requests[0].ball.mode, +ball_placement_t::END_FORCE);
  EXPECT_EQ(out.requests[0].robots[0].mode, +ball_placement_t::END_FORCE);

  ball->set_by_force(false);
  ball->set_vx(std::nanf(""));
  out = translate_simulator_command(command, &state, {});
  EXPECT_TRUE(has_code(out.errors, kErrorInvalid));
}

TEST(SslSimControl, RollAsksForARollingBall) {
  SimulatorCommand command;
  TeleportBall* ball = command.mutable_control()->mutable_teleport_ball();
  ball->set_x(1);
  ball->set_y(1);
  ball->set_vx(2);
  ball->set_roll(true);
  const auto out = translate_simulator_command(command, nullptr, {});
  ASSERT_EQ(out.requests.size(), 1u);
  EXPECT_TRUE(out.errors.empty());
  EXPECT_TRUE(out.requests[0].ball.rolling);
  EXPECT_EQ(out.requests[0].ball.mode, +ball_placement_t::TELEPORT);
}

TEST(SslSimControl, TeleportSafelyPushesARobotOffTheTarget) {
  const sim_state_t state = state_with_robot(team_t::YELLOW, 2, 1.02, 1.0, 0.5);
  SimulatorCommand command;
  TeleportBall* ball = command.mutable_control()->mutable_teleport_ball();
  ball->set_x(1);
  ball->set_y(1);
  ball->set_teleport_safely(true);
  SimControlSettings settings;
  const auto out = translate_simulator_command(command, &state, settings);
  ASSERT_EQ(out.requests.size(), 1u);
  ASSERT_EQ(out.requests[0].num_robots, 1);
  const robot_placement_t& moved = out.requests[0].robots[0];
  EXPECT_EQ(moved.robot_id, 2);
  EXPECT_TRUE(moved.present);
  const double distance = std::hypot(moved.x - 1.0, moved.y - 1.0);
  EXPECT_GE(distance, settings.robot_radius + settings.ball_radius);
  EXPECT_NEAR(moved.y, 1.0, 1e-9);  // pushed straight along the line from the ball
  EXPECT_DOUBLE_EQ(moved.orientation, 0.5);
  EXPECT_DOUBLE_EQ(moved.vx, 0.0);
}

TEST(SslSimControl, TeleportRobotFillsUnsetFieldsFromTheState) {
  const sim_state_t state = state_with_robot(team_t::BLUE, 4, -1.0, 2.0, 1.25);
  SimulatorCommand command;
  TeleportRobot* robot = command.mutable_control()->add_teleport_robot();
  robot->mutable_id()->set_id(4);
  robot->mutable_id()->set_team(BLUE);
  robot->set_x(0.5f);
  robot->set_v_angular(3.0f);
  const auto out = translate_simulator_command(command, &state, {});
  EXPECT_TRUE(out.errors.empty());
  ASSERT_EQ(out.requests.size(), 1u);
  ASSERT_EQ(out.requests[0].num_robots, 1);
  const robot_placement_t& p = out.requests[0].robots[0];
  EXPECT_EQ(p.team, +team_t::BLUE);
  EXPECT_EQ(p.robot_id, 4);
  EXPECT_TRUE(p.present);
  EXPECT_EQ(p.robot_type, "");  // keeps its type
  EXPECT_DOUBLE_EQ(p.x, 0.5);
  EXPECT_DOUBLE_EQ(p.y, 2.0);
  EXPECT_DOUBLE_EQ(p.orientation, 1.25);
  EXPECT_DOUBLE_EQ(p.omega, 3.0);
  EXPECT_FALSE(out.requests[0].has_ball);
}

TEST(SslSimControl, PresentAddsAndRemovesRobots) {
  SimulatorCommand command;
  TeleportRobot* add = command.mutable_control()->add_teleport_robot();
  add->mutable_id()->set_id(9);
  add->mutable_id()->set_team(YELLOW);
  add->set_x(1);
  add->set_y(2);
  add->set_present(true);
  TeleportRobot* remove = command.mutable_control()->add_teleport_robot();
  remove->mutable_id()->set_id(1);
  remove->mutable_id()->set_team(BLUE);
  remove->set_present(false);
  SimControlSettings settings;
  settings.new_robot_type = "omni3_cmdragons02";
  const auto out = translate_simulator_command(command, nullptr, settings);
  EXPECT_TRUE(out.errors.empty());
  ASSERT_EQ(out.requests.size(), 1u);
  ASSERT_EQ(out.requests[0].num_robots, 2);
  EXPECT_EQ(out.requests[0].robots[0].team, +team_t::YELLOW);
  EXPECT_TRUE(out.requests[0].robots[0].present);
  EXPECT_EQ(out.requests[0].robots[0].robot_type, "omni3_cmdragons02");
  EXPECT_EQ(out.requests[0].robots[1].team, +team_t::BLUE);
  EXPECT_FALSE(out.requests[0].robots[1].present);
}

TEST(SslSimControl, UnknownRobotOrTeamIsAnError) {
  SimulatorCommand command;
  TeleportRobot* robot = command.mutable_control()->add_teleport_robot();
  robot->mutable_id()->set_id(5);
  robot->mutable_id()->set_team(BLUE);
  robot->set_x(1);
  auto out = translate_simulator_command(command, nullptr, {});
  EXPECT_TRUE(out.requests.empty());
  EXPECT_TRUE(has_code(out.errors, kErrorUnknownRobot));
  robot->mutable_id()->set_team(UNKNOWN);
  out = translate_simulator_command(command, nullptr, {});
  EXPECT_TRUE(has_code(out.errors, kErrorInvalid));
}

TEST(SslSimControl, SimulationSpeed) {
  sim_state_t paused{};
  paused.paused = true;
  SimulatorCommand command;
  command.mutable_control()->set_simulation_speed(2.0f);
  auto out = translate_simulator_command(command, &paused, {});
  ASSERT_EQ(out.requests.size(), 2u);
  EXPECT_EQ(out.requests[0].action, +sim_control_t::SET_SPEED);
  EXPECT_DOUBLE_EQ(out.requests[0].speed_factor, 2.0);
  EXPECT_EQ(out.requests[1].action, +sim_control_t::RESUME);

  sim_state_t running{};
  out = translate_simulator_command(command, &running, {});
  EXPECT_EQ(out.requests.size(), 1u);

  command.mutable_control()->set_simulation_speed(0.0f);
  out = translate_simulator_command(command, &running, {});
  ASSERT_EQ(out.requests.size(), 1u);
  EXPECT_EQ(out.requests[0].action, +sim_control_t::PAUSE);

  command.mutable_control()->set_simulation_speed(-1.0f);
  out = translate_simulator_command(command, &running, {});
  EXPECT_TRUE(out.requests.empty());
  EXPECT_TRUE(has_code(out.errors, kErrorInvalid));
}

TEST(SslSimControl, GeometryBecomesSetFieldSpecsWithoutABaseTypeAreAnError) {
  SimulatorCommand command;
  SimulatorConfig* config = command.mutable_config();
  config->mutable_geometry()->mutable_field()->set_field_length(1);
  RobotSpecs* specs = config->add_robot_specs();
  specs->mutable_id()->set_id(0);
  config->mutable_realism_config();
  config->set_vision_port(10006);
  config->mutable_geometry()->mutable_field()->set_field_width(7400);
  config->mutable_geometry()->mutable_field()->set_line_thickness(20);
  config->mutable_geometry()->add_calib();  // all zero: no camera position, an invalid value
  const auto out = translate_simulator_command(command, nullptr, {});
  ASSERT_EQ(out.requests.size(), 1u);
  EXPECT_EQ(out.requests[0].action, +sim_control_t::SET_FIELD);
  EXPECT_NE(out.requests[0].field_config.find("FIELD_LENGTH = 0.001\n"), std::string::npos);
  EXPECT_NE(out.requests[0].field_config.find("FIELD_WIDTH = 7.4\n"), std::string::npos);
  EXPECT_NE(out.requests[0].field_config.find("LINE_WIDTH = 0.02\n"), std::string::npos);
  EXPECT_EQ(out.requests[0].field_config.find("PENALTY"), std::string::npos);  // unset: unchanged
  EXPECT_EQ(out.errors.size(), 2u);  // calib; robot specs without a base type
  EXPECT_TRUE(has_code(out.errors, kErrorUnsupported));
  EXPECT_TRUE(has_code(out.errors, kErrorInvalid));
  EXPECT_FALSE(out.cameras.has_value());
  EXPECT_FALSE(out.realism.has_value());  // no custom config: nothing to change
  ASSERT_TRUE(out.vision_port.has_value());
  EXPECT_EQ(*out.vision_port, 10006);
}

// ER-Force's simulate_dribbling reaches physics (which owns the dribblers) as
// SET_DRIBBLING, inverted: false there is "glue the ball", perfect dribbling.
TEST(SslSimControl, SimulateDribblingBecomesSetDribblingWithoutAnError) {
  for (const bool simulate : {false, true}) {
    RealismConfigErForce erforce;
    erforce.set_simulate_dribbling(simulate);
    SimulatorCommand command;
    command.mutable_config()->mutable_realism_config()->add_custom()->PackFrom(erforce);
    const auto out = translate_simulator_command(command, nullptr, {});
    for (const auto& e : out.errors) ADD_FAILURE() << e.code() << ": " << e.message();
    ASSERT_EQ(out.requests.size(), 1u);
    EXPECT_EQ(out.requests[0].action, +sim_control_t::SET_DRIBBLING);
    EXPECT_EQ(out.requests[0].perfect_dribbling, !simulate);
  }
  // Unset: physics is not asked.
  RealismConfigErForce quiet;
  quiet.set_stddev_ball_p(0.001f);
  SimulatorCommand command;
  command.mutable_config()->mutable_realism_config()->add_custom()->PackFrom(quiet);
  EXPECT_TRUE(translate_simulator_command(command, nullptr, {}).requests.empty());
}
