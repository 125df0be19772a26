#include "ubersim/dds_bridge/convert_sim_state.hpp"

#include <algorithm>
#include <iterator>

namespace ubersim::dds {
namespace {

// The fixed-size arrays of a body state have the same shape on both sides.
template <class From, class To>
void copy_body(const From& from, To& to) {
  std::copy(std::begin(from.position), std::end(from.position), std::begin(to.position));
  std::copy(std::begin(from.orientation), std::end(from.orientation), std::begin(to.orientation));
  std::copy(std::begin(from.linear_velocity), std::end(from.linear_velocity),
            std::begin(to.linear_velocity));
  std::copy(std::begin(from.angular_velocity), std::end(from.angular_velocity),
            std::begin(to.angular_velocity));
}

void robot_to_dds(const robot_state_t& from, DdsRobotState& to) {
  to.team = from.team;
  to.robot_id = from.robot_id;
  to.robot_type = dds_string(from.robot_type);
  to.x = from.x;
  to.y = from.y;
  to.orientation = from.orientation;
  to.vx = from.vx;
  to.vy = from.vy;
  to.omega = from.omega;
  copy_body(from.body, to.body);
  fill_sequence(to.wheel_speeds, from.wheel_speeds);
  to.ball_contact = from.ball_contact != 0;
  to.kicker_charged = from.kicker_charged != 0;
  to.last_command_time = from.last_command_time;
}

robot_state_t robot_from_dds(const DdsRobotState& from) {
  robot_state_t to{};
  to.team = from.team;
  to.robot_id = from.robot_id;
  to.robot_type = from_dds_string(from.robot_type);
  to.x = from.x;
  to.y = from.y;
  to.orientation = from.orientation;
  to.vx = from.vx;
  to.vy = from.vy;
  to.omega = from.omega;
  copy_body(from.body, to.body);
  to.wheel_speeds = from_dds_sequence(from.wheel_speeds);
  to.num_wheels = count_of(to.wheel_speeds);
  to.ball_contact = from.ball_contact ? 1 : 0;
  to.kicker_charged = from.kicker_charged ? 1 : 0;
  to.last_command_time = from.last_command_time;
  return to;
}

}  // namespace

OwnedSample<DdsSimState> to_dds(const sim_state_t& state) {
  OwnedSample<DdsSimState> sample;
  DdsSimState& to = sample.get();
  to.sim_time = state.sim_time;
  to.step = state.step;
  to.dt = state.dt;
  to.paused = state.paused != 0;
  to.speed_factor = state.speed_factor;
  copy_body(state.ball, to.ball);
  to.ball_present = state.ball_present != 0;
  fill_sequence(to.robots, state.robots, robot_to_dds);
  return sample;
}

sim_state_t from_dds(const DdsSimState& state) {
  sim_state_t to{};
  to.sim_time = state.sim_time;
  to.step = state.step;
  to.dt = state.dt;
  to.paused = state.paused ? 1 : 0;
  to.speed_factor = state.speed_factor;
  copy_body(state.ball, to.ball);
  to.ball_present = state.ball_present ? 1 : 0;
  to.robots = from_dds_sequence<robot_state_t>(state.robots, robot_from_dds);
  to.num_robots = count_of(to.robots);
  return to;
}

}  // namespace ubersim::dds
