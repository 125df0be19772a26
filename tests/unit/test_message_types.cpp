// Every message family survives encode -> decode with every field intact.
// Equality is checked by re-encoding the decoded message and comparing bytes,
// plus spot checks of fields, so a field lost or mis-sized in a .lcm file fails.
// Decoding goes through decode_bounded, as every process does, so the generated
// bounds are checked to accept every well-formed message.
#include <gtest/gtest.h>

#include <ubersim/field_geometry_t.hpp>
#include <ubersim/radio_feedback_t.hpp>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/sim_commands_t.hpp>
#include <ubersim/sim_control_ack_t.hpp>
#include <ubersim/sim_control_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <ubersim/team_t.hpp>
#include <ubersim/vision_frame_t.hpp>
#include <ubersim/vision_geometry_t.hpp>
#include <vector>

#include "ubersim/bounded_decode.hpp"

namespace {

template <class Msg>
Msg round_trip(const Msg& original) {
  std::vector<uint8_t> bytes(static_cast<size_t>(original.getEncodedSize()));
  EXPECT_EQ(original.encode(bytes.data(), 0, static_cast<int>(bytes.size())),
            static_cast<int>(bytes.size()));
  Msg decoded;
  EXPECT_TRUE(ubersim::decode_bounded(bytes.data(), bytes.size(), decoded));
  std::vector<uint8_t> again(static_cast<size_t>(decoded.getEncodedSize()));
  decoded.encode(again.data(), 0, static_cast<int>(again.size()));
  EXPECT_EQ(bytes, again);
  // A truncated message must not decode.
  Msg truncated;
  EXPECT_FALSE(ubersim::decode_bounded(bytes.data(), bytes.size() - 1, truncated));
  return decoded;
}

ubersim::robot_command_t make_command(int id) {
  ubersim::robot_command_t c{};
  c.robot_id = id;
  c.mode = ubersim::robot_command_t::MODE_WHEEL_SPEEDS;
  c.vx = 1.25;
  c.vy = -0.5;
  c.omega = 3.0;
  c.num_wheels = 4;
  c.wheel_speeds = {1.0, -2.0, 3.0, -4.0};
  c.kick_speed = 6.5;
  c.chip_speed = 3.0;
  c.chip_angle = 0.7;
  c.dribbler_speed = 300.0;
  return c;
}

}  // namespace

TEST(MessageTypes, VisionFrame) {
  ubersim::vision_frame_t frame{};
  frame.camera_id = 2;
  frame.frame_number = 123456789012LL;
  frame.t_capture = 10.0;
  frame.t_sent = 10.1;
  frame.num_balls = 1;
  frame.balls.push_back({0.9f, 1.5, -2.5, 320.5, 240.25, 71.5});
  frame.num_robots_yellow = 2;
  frame.robots_yellow = {{3, 0.8f, 1.0, 2.0, -3.0, 10.0, 20.0}, {7, 1.0f, -1, -2, 3.1, 1, 2}};
  frame.num_robots_blue = 1;
  frame.robots_blue = {{11, 0.5f, 4.0, -1.0, 0.5, 600, 400}};
  const auto decoded = round_trip(frame);
  EXPECT_EQ(decoded.frame_number, 123456789012LL);
  EXPECT_EQ(decoded.robots_yellow[1].robot_id, 7);
  EXPECT_DOUBLE_EQ(decoded.robots_blue[0].orientation, 0.5);
  EXPECT_DOUBLE_EQ(decoded.balls[0].pixel_y, 240.25);
  EXPECT_DOUBLE_EQ(decoded.balls[0].area, 71.5);
}

TEST(MessageTypes, VisionGeometryWithCameras) {
  ubersim::vision_geometry_t geometry{};
  geometry.t_sent = 1.0;
  geometry.field.name = "division_b";
  geometry.field.field_length = 9.0;
  geometry.field.field_width = 6.0;
  geometry.field.ball_radius = 0.0215;
  geometry.num_cameras = 1;
  ubersim::camera_calibration_t camera{};
  camera.camera_id = 0;
  camera.focal_length = 500;
  camera.image_width = 780;
  camera.position[2] = 4.0;
  camera.orientation[0] = 1.0;
  geometry.cameras.push_back(camera);
  const auto decoded = round_trip(geometry);
  EXPECT_EQ(decoded.field.name, "division_b");
  EXPECT_DOUBLE_EQ(decoded.cameras[0].position[2], 4.0);
  EXPECT_EQ(decoded.cameras[0].image_width, 780);
}

TEST(MessageTypes, FieldGeometry) {
  ubersim::field_geometry_t field{};
  field.name = "field2002";
  field.field_length = 2.8;
  field.goal_width = 0.5;
  const auto decoded = round_trip(field);
  EXPECT_DOUBLE_EQ(decoded.goal_width, 0.5);
}

TEST(MessageTypes, RadioPacket) {
  ubersim::radio_packet_t packet{};
  packet.team = ubersim::team_t::BLUE;
  packet.sequence = 42;
  packet.t_sent = 3.5;
  packet.num_commands = 2;
  packet.commands = {make_command(1), make_command(9)};
  const auto decoded = round_trip(packet);
  EXPECT_EQ(decoded.team, +ubersim::team_t::BLUE);
  EXPECT_EQ(decoded.commands[1].robot_id, 9);
  EXPECT_DOUBLE_EQ(decoded.commands[0].wheel_speeds[3], -4.0);
  EXPECT_DOUBLE_EQ(decoded.commands[0].dribbler_speed, 300.0);
}

TEST(MessageTypes, SimCommands) {
  ubersim::sim_commands_t commands{};
  commands.team = ubersim::team_t::YELLOW;
  commands.sequence = 7;
  commands.t_received = 1.0;
  commands.t_apply = 1.1;
  commands.command_timeout = 0.5;
  commands.num_commands = 1;
  commands.commands = {make_command(2)};
  const auto decoded = round_trip(commands);
  EXPECT_DOUBLE_EQ(decoded.t_apply, 1.1);
  EXPECT_DOUBLE_EQ(decoded.command_timeout, 0.5);
}

TEST(MessageTypes, SimState) {
  ubersim::sim_state_t state{};
  state.sim_time = 12.5;
  state.step = 3000;
  state.dt = 1.0 / 240;
  state.speed_factor = 1.0;
  state.ball_present = true;
  state.ball.position[0] = 0.3;
  state.ball.orientation[0] = 1.0;
  state.ball.angular_velocity[2] = 5.0;
  state.num_robots = 1;
  ubersim::robot_state_t robot{};
  robot.team = ubersim::team_t::BLUE;
  robot.robot_id = 5;
  robot.robot_type = "omni4_ssl";
  robot.x = 1.0;
  robot.omega = -1.0;
  robot.num_wheels = 3;
  robot.wheel_speeds = {1, 2, 3};
  robot.ball_contact = true;
  robot.kicker_charged = true;
  robot.last_command_time = 12.4;
  state.robots.push_back(robot);
  const auto decoded = round_trip(state);
  EXPECT_EQ(decoded.step, 3000);
  EXPECT_EQ(decoded.robots[0].robot_type, "omni4_ssl");
  EXPECT_TRUE(decoded.robots[0].ball_contact);
  EXPECT_DOUBLE_EQ(decoded.ball.angular_velocity[2], 5.0);
  EXPECT_DOUBLE_EQ(decoded.robots[0].wheel_speeds[2], 3.0);
}

TEST(MessageTypes, SimControl) {
  ubersim::sim_control_t control{};
  control.request_id = 99;
  control.sender = "referee";
  control.action = ubersim::sim_control_t::SETUP;
  control.num_robots = 1;
  ubersim::robot_placement_t placement{};
  placement.team = ubersim::team_t::YELLOW;
  placement.robot_id = 3;
  placement.robot_type = "diff_drive_cmdragons02";
  placement.present = true;
  placement.x = -1.0;
  placement.orientation = 1.57;
  placement.vx = 0.5;
  control.robots.push_back(placement);
  control.has_ball = true;
  control.ball.position[0] = 0.1;
  control.ball.linear_velocity[1] = 2.0;
  control.step_count = 10;
  control.speed_factor = 4.0;
  control.seed = 1234567890123LL;
  const auto decoded = round_trip(control);
  EXPECT_EQ(decoded.action,
            +ubersim::sim_control_t::SETUP);  // + : LCM constants have no out-of-class definition
  EXPECT_EQ(decoded.robots[0].robot_type, "diff_drive_cmdragons02");
  EXPECT_DOUBLE_EQ(decoded.ball.linear_velocity[1], 2.0);
  EXPECT_EQ(decoded.seed, 1234567890123LL);
}

TEST(MessageTypes, SimControlAck) {
  ubersim::sim_control_ack_t ack{};
  ack.request_id = 99;
  ack.sender = "referee";
  ack.ok = false;
  ack.message = "unknown robot type 'foo'";
  ack.sim_time = 2.0;
  ack.step = 480;
  const auto decoded = round_trip(ack);
  EXPECT_FALSE(decoded.ok);
  EXPECT_EQ(decoded.message, "unknown robot type 'foo'");
}

TEST(MessageTypes, RadioFeedback) {
  ubersim::radio_feedback_t feedback{};
  feedback.team = ubersim::team_t::YELLOW;
  feedback.t_measured = 1.0;
  feedback.t_sent = 1.02;
  feedback.num_robots = 2;
  feedback.robots = {{0, true, false}, {1, false, true}};
  const auto decoded = round_trip(feedback);
  EXPECT_TRUE(decoded.robots[0].ball_contact);
  EXPECT_TRUE(decoded.robots[1].kicker_charged);
}
