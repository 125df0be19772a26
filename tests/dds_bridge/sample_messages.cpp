#include "sample_messages.hpp"

#include <cmath>
#include <string>
#include <ubersim/robot_command_t.hpp>
#include <ubersim/sim_control_t.hpp>

namespace dds_test {

using namespace ubersim;

namespace {

vision_robot_t vision_robot(std::int32_t id, double base) {
  vision_robot_t r{};
  r.robot_id = id;
  r.confidence = static_cast<float>(0.5 + 0.01 * id);
  r.x = base + 0.11;
  r.y = base - 0.12;
  r.orientation = std::remainder(base * 0.3, 2 * M_PI);
  r.pixel_x = 100 + base;
  r.pixel_y = 200 + base;
  return r;
}

body_state_t body(double base) {
  body_state_t b{};
  for (int i = 0; i < 3; ++i) {
    b.position[i] = base + 0.1 * i;
    b.linear_velocity[i] = base + 0.2 * i + 0.01;
    b.angular_velocity[i] = base + 0.3 * i + 0.02;
  }
  for (int i = 0; i < 4; ++i) b.orientation[i] = 0.5 + 0.01 * i + 0.001 * base;
  return b;
}

}  // namespace

vision_frame_t vision_frame(std::int64_t frame_number, int balls, int robots_per_team) {
  vision_frame_t f{};
  f.camera_id = 3;
  f.frame_number = frame_number;
  f.t_capture = 12.5 + static_cast<double>(frame_number) / 60;
  f.t_sent = f.t_capture + 0.0042;
  for (int i = 0; i < balls; ++i) {
    vision_ball_t b{};
    b.confidence = static_cast<float>(0.9 - 0.1 * i);
    b.x = 1.25 + i;
    b.y = -0.75 - i;
    b.pixel_x = 321.5 + i;
    b.pixel_y = 123.25 + i;
    b.area = 71.5 + i;
    f.balls.push_back(b);
  }
  for (int i = 0; i < robots_per_team; ++i) {
    f.robots_yellow.push_back(vision_robot(i, -2.0 + 0.3 * i));
    f.robots_blue.push_back(vision_robot(i + 8, 2.0 - 0.3 * i));
  }
  f.num_balls = static_cast<std::int32_t>(f.balls.size());
  f.num_robots_yellow = static_cast<std::int32_t>(f.robots_yellow.size());
  f.num_robots_blue = static_cast<std::int32_t>(f.robots_blue.size());
  return f;
}

field_geometry_t field_geometry(double seed) {
  field_geometry_t g{};
  g.name = "division_b";
  g.field_length = 9.0 + seed;
  g.field_width = 6.0 + seed;
  g.boundary_width = 0.3;
  g.line_width = 0.01;
  g.goal_width = 1.0;
  g.goal_depth = 0.18;
  g.goal_height = 0.155;
  g.goal_wall_thickness = 0.02;
  g.wall_height = 0.1;
  g.wall_thickness = 0.05;
  g.center_circle_radius = 0.5;
  g.penalty_area_depth = 1.0;
  g.penalty_area_width = 2.0;
  g.ball_radius = 0.0215;
  g.penalty_mark_distance = 6.0;
  g.boundary_width_goal_line = 0.6;
  g.goal_substitution_area_width = 0.3;
  return g;
}

vision_geometry_t vision_geometry(double seed) {
  vision_geometry_t g{};
  g.t_sent = 3.25 + seed;
  g.field = field_geometry(seed);
  for (int c = 0; c < 2; ++c) {
    camera_calibration_t cam{};
    cam.camera_id = c;
    cam.focal_length = 800 + c;
    cam.principal_x = 390 + c;
    cam.principal_y = 290 + c;
    cam.image_width = 780;
    cam.image_height = 580;
    for (int i = 0; i < 3; ++i) cam.position[i] = (c == 0 ? -2.25 : 2.25) + 0.1 * i;
    for (int i = 0; i < 4; ++i) cam.orientation[i] = 0.1 * (i + 1) + 0.01 * c;
    cam.distortion = 0.2 - 0.05 * c;
    g.cameras.push_back(cam);
  }
  g.num_cameras = static_cast<std::int32_t>(g.cameras.size());
  return g;
}

robot_command_t velocity_command(std::int32_t robot_id, double seed) {
  robot_command_t c{};
  c.robot_id = robot_id;
  c.mode = robot_command_t::MODE_LOCAL_VELOCITY;
  c.vx = 1.5 + 0.1 * robot_id + seed;
  c.vy = -0.5 + 0.05 * robot_id;
  c.omega = 2.25 - 0.1 * robot_id;
  c.kick_speed = 4.5;
  c.chip_speed = 0;
  c.chip_angle = 0;
  c.dribbler_speed = 300 + robot_id;
  return c;
}

robot_command_t wheel_command(std::int32_t robot_id, int wheels, double seed) {
  robot_command_t c{};
  c.robot_id = robot_id;
  c.mode = robot_command_t::MODE_WHEEL_SPEEDS;
  for (int w = 0; w < wheels; ++w) c.wheel_speeds.push_back(10.5 * (w + 1) - 7 + seed);
  c.num_wheels = wheels;
  c.kick_speed = 0;
  c.chip_speed = 3.5;
  c.chip_angle = 0.7;
  c.dribbler_speed = -50;
  return c;
}

radio_packet_t radio_packet(std::int8_t team, std::int64_t sequence) {
  radio_packet_t p{};
  p.team = team;
  p.sequence = sequence;
  p.t_sent = 7.125 + 0.001 * static_cast<double>(sequence);
  p.commands = {velocity_command(0), velocity_command(3, 0.25), wheel_command(5, 4)};
  p.num_commands = static_cast<std::int32_t>(p.commands.size());
  return p;
}

radio_feedback_t radio_feedback(std::int8_t team, double seed) {
  radio_feedback_t f{};
  f.team = team;
  f.t_measured = 4.5 + seed;
  f.t_sent = 4.55 + seed;
  for (int i = 0; i < 3; ++i) {
    robot_feedback_t r{};
    r.robot_id = i * 2;
    r.ball_contact = i == 1;
    r.kicker_charged = i != 2;
    f.robots.push_back(r);
  }
  f.num_robots = static_cast<std::int32_t>(f.robots.size());
  return f;
}

sim_commands_t sim_commands(std::int8_t team, std::int64_t sequence) {
  const radio_packet_t p = radio_packet(team, sequence);
  sim_commands_t c{};
  c.team = team;
  c.sequence = sequence;
  c.t_received = 7.2;
  c.t_apply = 7.233;
  c.command_timeout = 0.25;
  c.commands = p.commands;
  c.num_commands = p.num_commands;
  return c;
}

sim_state_t sim_state(std::int64_t step, int robots_per_team) {
  sim_state_t s{};
  s.dt = 1.0 / 240;
  s.step = step;
  s.sim_time = static_cast<double>(step) * s.dt;
  s.paused = 0;
  s.speed_factor = 1;
  s.ball = body(0.25);
  s.ball_present = 1;
  for (int team = 0; team < 2; ++team) {
    for (int i = 0; i < robots_per_team; ++i) {
      robot_state_t r{};
      const double base = (team == 0 ? -3.0 : 3.0) + 0.25 * i + 1e-4 * static_cast<double>(step);
      r.team = static_cast<std::int8_t>(team);
      r.robot_id = i;
      r.robot_type = i % 2 == 0 ? "omni4_ssl" : "omni3_cmdragons02";
      r.x = base;
      r.y = -base / 2;
      r.orientation = std::remainder(base, 2 * M_PI);
      r.vx = 0.1 * i;
      r.vy = -0.1 * i;
      r.omega = 0.01 * i;
      r.body = body(base);
      for (int w = 0; w < 4; ++w) r.wheel_speeds.push_back(base * (w + 1));
      r.num_wheels = 4;
      r.ball_contact = i == 3;
      r.kicker_charged = i != 4;
      r.last_command_time = i == 0 ? -1.0 : s.sim_time - 0.01;
      s.robots.push_back(r);
    }
  }
  s.num_robots = static_cast<std::int32_t>(s.robots.size());
  return s;
}

sim_control_t sim_control(std::int64_t request_id) {
  sim_control_t c{};
  c.request_id = request_id;
  c.sender = "dds test";
  c.action = sim_control_t::PLACE;
  for (int i = 0; i < 2; ++i) {
    robot_placement_t p{};
    p.team = static_cast<std::int8_t>(i);
    p.robot_id = 4 + i;
    p.robot_type = i == 0 ? "omni4_ssl" : "";
    p.present = 1;
    p.x = -1.5 + i;
    p.y = 0.75 - i;
    p.orientation = 0.5 * i + 0.1;
    p.vx = 0.2;
    p.vy = -0.3;
    p.omega = 0.4;
    c.robots.push_back(p);
  }
  c.num_robots = static_cast<std::int32_t>(c.robots.size());
  c.has_ball = 1;
  for (int i = 0; i < 3; ++i) {
    c.ball.position[i] = 0.5 * (i + 1);
    c.ball.linear_velocity[i] = -0.25 * (i + 1);
  }
  c.step_count = 17;
  c.speed_factor = 2.5;
  c.seed = 123456789012345;
  return c;
}

sim_control_ack_t sim_control_ack(std::int64_t request_id) {
  sim_control_ack_t a{};
  a.request_id = request_id;
  a.sender = "dds test";
  a.ok = 1;
  a.message = "placed 2 robots";
  a.sim_time = 42.125;
  a.step = 10110;
  return a;
}

}  // namespace dds_test
