#include "ubersim/dds_bridge/convert_radio.hpp"

namespace ubersim::dds {
namespace {

void command_to_dds(const robot_command_t& from, DdsRobotCommand& to) {
  to.robot_id = from.robot_id;
  to.mode = from.mode;
  to.vx = from.vx;
  to.vy = from.vy;
  to.omega = from.omega;
  fill_sequence(to.wheel_speeds, from.wheel_speeds);
  to.kick_speed = from.kick_speed;
  to.chip_speed = from.chip_speed;
  to.chip_angle = from.chip_angle;
  to.dribbler_speed = from.dribbler_speed;
}

robot_command_t command_from_dds(const DdsRobotCommand& from) {
  robot_command_t to{};
  to.robot_id = from.robot_id;
  to.mode = from.mode;
  to.vx = from.vx;
  to.vy = from.vy;
  to.omega = from.omega;
  to.wheel_speeds = from_dds_sequence(from.wheel_speeds);
  to.num_wheels = count_of(to.wheel_speeds);
  to.kick_speed = from.kick_speed;
  to.chip_speed = from.chip_speed;
  to.chip_angle = from.chip_angle;
  to.dribbler_speed = from.dribbler_speed;
  return to;
}

void feedback_to_dds(const robot_feedback_t& from, DdsRobotFeedback& to) {
  to.robot_id = from.robot_id;
  to.ball_contact = from.ball_contact != 0;
  to.kicker_charged = from.kicker_charged != 0;
}

robot_feedback_t feedback_from_dds(const DdsRobotFeedback& from) {
  robot_feedback_t to{};
  to.robot_id = from.robot_id;
  to.ball_contact = from.ball_contact ? 1 : 0;
  to.kicker_charged = from.kicker_charged ? 1 : 0;
  return to;
}

}  // namespace

OwnedSample<DdsRadioPacket> to_dds(const radio_packet_t& packet) {
  OwnedSample<DdsRadioPacket> sample;
  DdsRadioPacket& to = sample.get();
  to.team = packet.team;
  to.sequence_number = packet.sequence;
  to.t_sent = packet.t_sent;
  fill_sequence(to.commands, packet.commands, command_to_dds);
  return sample;
}

radio_packet_t from_dds(const DdsRadioPacket& packet) {
  radio_packet_t to{};
  to.team = packet.team;
  to.sequence = packet.sequence_number;
  to.t_sent = packet.t_sent;
  to.commands = from_dds_sequence<robot_command_t>(packet.commands, command_from_dds);
  to.num_commands = count_of(to.commands);
  return to;
}

OwnedSample<DdsRadioFeedback> to_dds(const radio_feedback_t& feedback) {
  OwnedSample<DdsRadioFeedback> sample;
  DdsRadioFeedback& to = sample.get();
  to.team = feedback.team;
  to.t_measured = feedback.t_measured;
  to.t_sent = feedback.t_sent;
  fill_sequence(to.robots, feedback.robots, feedback_to_dds);
  return sample;
}

radio_feedback_t from_dds(const DdsRadioFeedback& feedback) {
  radio_feedback_t to{};
  to.team = feedback.team;
  to.t_measured = feedback.t_measured;
  to.t_sent = feedback.t_sent;
  to.robots = from_dds_sequence<robot_feedback_t>(feedback.robots, feedback_from_dds);
  to.num_robots = count_of(to.robots);
  return to;
}

OwnedSample<DdsSimCommands> to_dds(const sim_commands_t& commands) {
  OwnedSample<DdsSimCommands> sample;
  DdsSimCommands& to = sample.get();
  to.team = commands.team;
  to.sequence_number = commands.sequence;
  to.t_received = commands.t_received;
  to.t_apply = commands.t_apply;
  to.command_timeout = commands.command_timeout;
  fill_sequence(to.commands, commands.commands, command_to_dds);
  return sample;
}

sim_commands_t from_dds(const DdsSimCommands& commands) {
  sim_commands_t to{};
  to.team = commands.team;
  to.sequence = commands.sequence_number;
  to.t_received = commands.t_received;
  to.t_apply = commands.t_apply;
  to.command_timeout = commands.command_timeout;
  to.commands = from_dds_sequence<robot_command_t>(commands.commands, command_from_dds);
  to.num_commands = count_of(to.commands);
  return to;
}

}  // namespace ubersim::dds
