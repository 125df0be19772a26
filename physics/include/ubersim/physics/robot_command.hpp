#pragma once
// A robot command after validation: every value finite and within the robot's
// limits. Only these ever reach the physics.
#include <string>
#include <ubersim/robot_command_t.hpp>
#include <vector>

#include "ubersim/robot_config.hpp"

namespace ubersim::physics {

enum class CommandMode { LocalVelocity, GlobalVelocity, WheelSpeeds };

struct RobotCommand {
  CommandMode mode = CommandMode::LocalVelocity;
  double vx = 0, vy = 0, omega = 0;  // m/s, m/s, rad/s (robot or field frame per mode)
  std::vector<double> wheel_speeds;  // rad/s, WheelSpeeds mode
  double kick_speed = 0;             // m/s, 0 = none
  double chip_speed = 0;             // m/s, 0 = none
  double chip_angle = 0;             // rad, resolved (never 0 when chip_speed > 0)
  double dribbler_speed = 0;         // rad/s of the roller
};

struct CommandCheck {
  bool accepted = false;  // false: dropped, keep the previous command
  bool clamped = false;   // accepted with values changed to fit the robot
  std::string problem;    // what was wrong, for the log
  RobotCommand command;
};

// Drops a command with a non-finite value, an unknown mode or the wrong number
// of wheel speeds; clamps values beyond the robot's limits.
CommandCheck check_command(const robot_command_t& raw, const RobotTypeConfig& robot);

}  // namespace ubersim::physics
