#include "ubersim/dds_bridge/convert_sim_control.hpp"

#include <algorithm>
#include <iterator>

namespace ubersim::dds {
namespace {

void placement_to_dds(const robot_placement_t& from, DdsRobotPlacement& to) {
  to.team = from.team;
  to.robot_id = from.robot_id;
  to.robot_type = dds_string(from.robot_type);
  to.present = from.present != 0;
  to.x = from.x;
  to.y = from.y;
  to.orientation = from.orientation;
  to.vx = from.vx;
  to.vy = from.vy;
  to.omega = from.omega;
}

robot_placement_t placement_from_dds(const DdsRobotPlacement& from) {
  robot_placement_t to{};
  to.team = from.team;
  to.robot_id = from.robot_id;
  to.robot_type = from_dds_string(from.robot_type);
  to.present = from.present ? 1 : 0;
  to.x = from.x;
  to.y = from.y;
  to.orientation = from.orientation;
  to.vx = from.vx;
  to.vy = from.vy;
  to.omega = from.omega;
  return to;
}

template <class From, class To>
void copy_ball(const From& from, To& to) {
  std::copy(std::begin(from.position), std::end(from.position), std::begin(to.position));
  std::copy(std::begin(from.linear_velocity), std::end(from.linear_velocity),
            std::begin(to.linear_velocity));
}

}  // namespace

OwnedSample<DdsSimControl> to_dds(const sim_control_t& control) {
  OwnedSample<DdsSimControl> sample;
  DdsSimControl& to = sample.get();
  to.request_id = control.request_id;
  to.sender = dds_string(control.sender);
  to.action = control.action;
  fill_sequence(to.robots, control.robots, placement_to_dds);
  to.has_ball = control.has_ball != 0;
  copy_ball(control.ball, to.ball);
  to.step_count = control.step_count;
  to.speed_factor = control.speed_factor;
  to.seed = control.seed;
  return sample;
}

sim_control_t from_dds(const DdsSimControl& control) {
  sim_control_t to{};
  to.request_id = control.request_id;
  to.sender = from_dds_string(control.sender);
  to.action = control.action;
  to.robots = from_dds_sequence<robot_placement_t>(control.robots, placement_from_dds);
  to.num_robots = count_of(to.robots);
  to.has_ball = control.has_ball ? 1 : 0;
  copy_ball(control.ball, to.ball);
  to.step_count = control.step_count;
  to.speed_factor = control.speed_factor;
  to.seed = control.seed;
  return to;
}

OwnedSample<DdsSimControlAck> to_dds(const sim_control_ack_t& ack) {
  OwnedSample<DdsSimControlAck> sample;
  DdsSimControlAck& to = sample.get();
  to.request_id = ack.request_id;
  to.sender = dds_string(ack.sender);
  to.ok = ack.ok != 0;
  to.message = dds_string(ack.message);
  to.sim_time = ack.sim_time;
  to.step = ack.step;
  return sample;
}

sim_control_ack_t from_dds(const DdsSimControlAck& ack) {
  sim_control_ack_t to{};
  to.request_id = ack.request_id;
  to.sender = from_dds_string(ack.sender);
  to.ok = ack.ok ? 1 : 0;
  to.message = from_dds_string(ack.message);
  to.sim_time = ack.sim_time;
  to.step = ack.step;
  return to;
}

}  // namespace ubersim::dds
