// RobotControl -> radio_packet_t and feedback -> RobotControlResponse, in-process.
#include <gtest/gtest.h>

#include <cmath>
#include <ubersim/robot_command_t.hpp>
#include <ubersim/team_t.hpp>

#include "ubersim/ssl_bridge/robot_control_translation.hpp"
#include "ubersim/ssl_bridge/units.hpp"

using namespace ubersim;
using namespace ubersim::ssl;

TEST(SslRobotControl, LocalVelocityKickAndDribbler) {
  RobotControl control;
  RobotCommand* c = control.add_robot_commands();
  c->set_id(3);
  MoveLocalVelocity* v = c->mutable_move_command()->mutable_local_velocity();
  v->set_forward(1.5f);
  v->set_left(-0.25f);
  v->set_angular(2.0f);
  c->set_kick_speed(5.0f);
  c->set_dribbler_speed(600.0f);
  const auto out = translate_robot_control(control, Team::Blue, std::nullopt);
  EXPECT_TRUE(out.errors.empty());
  EXPECT_EQ(out.packet.team, +team_t::BLUE);
  ASSERT_EQ(out.packet.num_commands, 1);
  const robot_command_t& r = out.packet.commands[0];
  EXPECT_EQ(r.robot_id, 3);
  EXPECT_EQ(r.mode, +robot_command_t::MODE_LOCAL_VELOCITY);
  EXPECT_DOUBLE_EQ(r.vx, 1.5);
  EXPECT_DOUBLE_EQ(r.vy, -0.25);
  EXPECT_DOUBLE_EQ(r.omega, 2.0);
  EXPECT_DOUBLE_EQ(r.kick_speed, 5.0);
  EXPECT_DOUBLE_EQ(r.chip_speed, 0.0);
  EXPECT_DOUBLE_EQ(r.dribbler_speed, 20 * M_PI);  // 600 rpm = 10 turns/s
}

TEST(SslRobotControl, KickAngleMakesAChipInRadians) {
  RobotControl control;
  RobotCommand* c = control.add_robot_commands();
  c->set_id(1);
  MoveGlobalVelocity* v = c->mutable_move_command()->mutable_global_velocity();
  v->set_x(-1.0f);
  v->set_y(0.5f);
  v->set_angular(0.0f);
  c->set_kick_speed(3.0f);
  c->set_kick_angle(45.0f);
  const auto out = translate_robot_control(control, Team::Yellow, std::nullopt);
  EXPECT_TRUE(out.errors.empty());
  EXPECT_EQ(out.packet.team, +team_t::YELLOW);
  const robot_command_t& r = out.packet.commands.at(0);
  EXPECT_EQ(r.mode, +robot_command_t::MODE_GLOBAL_VELOCITY);
  EXPECT_DOUBLE_EQ(r.vx, -1.0);
  EXPECT_DOUBLE_EQ(r.vy, 0.5);
  EXPECT_DOUBLE_EQ(r.kick_speed, 0.0);
  EXPECT_DOUBLE_EQ(r.chip_speed, 3.0);
  EXPECT_DOUBLE_EQ(r.chip_angle, M_PI / 4);
}

TEST(SslRobotControl, NoMoveCommandStandsStill) {
  RobotControl control;
  control.add_robot_commands()->set_id(0);
  const auto out = translate_robot_control(control, Team::Blue, std::nullopt);
  ASSERT_EQ(out.packet.num_commands, 1);
  EXPECT_EQ(out.packet.commands[0].mode, +robot_command_t::MODE_LOCAL_VELOCITY);
  EXPECT_DOUBLE_EQ(out.packet.commands[0].vx, 0.0);
}

TEST(SslRobotControl, BadValuesAreErrors) {
  RobotControl control;
  RobotCommand* nan_move = control.add_robot_commands();
  nan_move->set_id(1);
  MoveLocalVelocity* v = nan_move->mutable_move_command()->mutable_local_velocity();
  v->set_forward(std::nanf(""));
  v->set_left(0);
  v->set_angular(0);
  RobotCommand* bad_kick = control.add_robot_commands();
  bad_kick->set_id(2);
  bad_kick->set_kick_speed(-1.0f);
  RobotCommand* wheels = control.add_robot_commands();
  wheels->set_id(3);
  MoveWheelVelocity* w = wheels->mutable_move_command()->mutable_wheel_velocity();
  w->set_front_right(1);
  w->set_back_right(1);
  w->set_back_left(1);
  w->set_front_left(1);
  const auto out = translate_robot_control(control, Team::Blue, std::nullopt);
  EXPECT_EQ(out.errors.size(), 3u);
  // The NaN command and the wheel command (no mapping) are dropped; the bad
  // kick only loses its kick.
  ASSERT_EQ(out.packet.num_commands, 1);
  EXPECT_EQ(out.packet.commands[0].robot_id, 2);
  EXPECT_DOUBLE_EQ(out.packet.commands[0].kick_speed, 0.0);
}

TEST(SslRobotControl, WheelVelocityForTheShippedOmniRobot) {
  const RobotTypeConfig type = load_robot_config(UBERSIM_SOURCE_CONFIG_DIR, "omni4_ssl");
  const auto mapping = wheel_mapping(type);
  ASSERT_TRUE(mapping.has_value());
  // omni4_ssl wheels at 57, 135, 225, 303 degrees: FL, BL, BR, FR.
  EXPECT_EQ(mapping->wheel_index[0], 3);  // front right
  EXPECT_EQ(mapping->wheel_index[1], 2);  // back right
  EXPECT_EQ(mapping->wheel_index[2], 1);  // back left
  EXPECT_EQ(mapping->wheel_index[3], 0);  // front left
  RobotControl control;
  RobotCommand* c = control.add_robot_commands();
  c->set_id(5);
  MoveWheelVelocity* w = c->mutable_move_command()->mutable_wheel_velocity();
  w->set_front_right(1.0f);
  w->set_back_right(2.0f);
  w->set_back_left(-0.5f);
  w->set_front_left(0.25f);
  const auto out = translate_robot_control(control, Team::Blue, mapping);
  EXPECT_TRUE(out.errors.empty());
  const robot_command_t& r = out.packet.commands.at(0);
  EXPECT_EQ(r.mode, +robot_command_t::MODE_WHEEL_SPEEDS);
  ASSERT_EQ(r.num_wheels, 4);
  EXPECT_DOUBLE_EQ(r.wheel_speeds[3], 1.0 / type.wheel_radius);
  EXPECT_DOUBLE_EQ(r.wheel_speeds[2], 2.0 / type.wheel_radius);
  EXPECT_DOUBLE_EQ(r.wheel_speeds[1], -0.5 / type.wheel_radius);
  EXPECT_DOUBLE_EQ(r.wheel_speeds[0], 0.25 / type.wheel_radius);
}

TEST(SslRobotControl, ThreeWheelRobotHasNoMapping) {
  const RobotTypeConfig type = load_robot_config(UBERSIM_SOURCE_CONFIG_DIR, "omni3_cmdragons02");
  EXPECT_FALSE(wheel_mapping(type).has_value());
}

TEST(SslRobotControl, FeedbackCarriesBallContact) {
  radio_feedback_t feedback{};
  robot_feedback_t a{};
  a.robot_id = 1;
  a.ball_contact = true;
  robot_feedback_t b{};
  b.robot_id = 4;
  feedback.robots = {a, b};
  feedback.num_robots = 2;
  RobotControlResponse response;
  add_feedback(&feedback, response);
  ASSERT_EQ(response.feedback_size(), 2);
  EXPECT_EQ(response.feedback(0).id(), 1u);
  EXPECT_TRUE(response.feedback(0).dribbler_ball_contact());
  EXPECT_EQ(response.feedback(1).id(), 4u);
  EXPECT_FALSE(response.feedback(1).dribbler_ball_contact());
  RobotControlResponse none;
  add_feedback(nullptr, none);
  EXPECT_EQ(none.feedback_size(), 0);
}
