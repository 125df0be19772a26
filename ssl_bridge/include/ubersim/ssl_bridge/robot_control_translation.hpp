#pragma once
// SSL simulation protocol RobotControl -> ubersim radio_packet_t (sent on
// RADIO_<TEAM>, so it goes through the radio emulator like any command), and
// RADIO_FEEDBACK_<TEAM> -> RobotControlResponse.
#include <ssl_simulation_robot_control.pb.h>
#include <ssl_simulation_robot_feedback.pb.h>

#include <array>
#include <optional>
#include <ubersim/radio_feedback_t.hpp>
#include <ubersim/radio_packet_t.hpp>

#include "ubersim/channels.hpp"
#include "ubersim/robot_config.hpp"
#include "ubersim/ssl_bridge/errors.hpp"

namespace ubersim::ssl {

// How the protocol's four wheels (front right, back right, back left, front
// left) map onto a robot type's wheel list, and the wheel radius that turns
// the protocol's wheel surface speeds (m/s) into our wheel speeds (rad/s).
struct WheelMapping {
  std::array<int, 4> wheel_index{};  // ours, for FR, BR, BL, FL
  int num_wheels = 0;
  double wheel_radius = 0;  // m
};

// A mapping when the type has exactly one wheel in each quadrant, else none.
std::optional<WheelMapping> wheel_mapping(const RobotTypeConfig& type);

struct RobotControlTranslation {
  radio_packet_t packet;  // team, commands; sequence and t_sent left to the caller
  Errors errors;
};

RobotControlTranslation translate_robot_control(const RobotControl& control, Team team,
                                                const std::optional<WheelMapping>& wheels);

// Feedback of every robot in the latest radio feedback (null: none yet).
void add_feedback(const radio_feedback_t* feedback, RobotControlResponse& response);

}  // namespace ubersim::ssl
