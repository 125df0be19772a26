#include "ubersim/physics/robot_command.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

namespace ubersim::physics {
namespace {

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

std::uint32_t bit(CommandLimit limit) {
  return 1U << static_cast<unsigned>(limit);
}

// What a check found beyond the robot's limits: the text only when needed
// (this runs for every command of every robot).
struct Findings {
  std::string problems;
  std::uint32_t limits = 0;

  void note(CommandLimit limit, const std::string& text) {
    problems += text + "; ";
    limits |= bit(limit);
  }
};

// Clamps |value| to limit, noting what it did.
double clamp_magnitude(double value, double limit, CommandLimit which, const char* unit,
                       Findings& found) {
  if (std::abs(value) <= limit) return value;
  found.note(which, std::string(command_limit_name(which)) + " " + number(value) + " " + unit +
                        " clamped to " + number(limit));
  return std::copysign(limit, value);
}

}  // namespace

const char* command_limit_name(CommandLimit limit) {
  switch (limit) {
    case CommandLimit::Speed:
      return "speed";
    case CommandLimit::AngularSpeed:
      return "angular speed";
    case CommandLimit::WheelSpeed:
      return "wheel speed";
    case CommandLimit::KickSpeed:
      return "kick speed";
    case CommandLimit::ChipSpeed:
      return "chip speed";
    case CommandLimit::ChipAngle:
      return "chip angle";
    case CommandLimit::DribblerSpeed:
      return "dribbler speed";
    case CommandLimit::NegativeKick:
      return "negative kick speed";
    case CommandLimit::NegativeChipAngle:
      return "negative chip angle";
    case CommandLimit::Count:
      break;
  }
  return "?";
}

void ClampCounts::add(const CommandCheck& check) {
  if (!check.clamped) return;
  ++commands;
  for (std::size_t i = 0; i < kCommandLimits; ++i) {
    if ((check.limits_hit & bit(static_cast<CommandLimit>(i))) != 0) ++by_limit[i];
  }
}

std::string ClampCounts::text() const {
  std::string out = std::to_string(commands);
  std::string parts;
  for (std::size_t i = 0; i < kCommandLimits; ++i) {
    if (by_limit[i] == 0) continue;
    parts += (parts.empty() ? "" : ", ") +
             std::string(command_limit_name(static_cast<CommandLimit>(i))) + " " +
             std::to_string(by_limit[i]);
  }
  return parts.empty() ? out : out + " (" + parts + ")";
}

CommandCheck check_command(const robot_command_t& raw, const RobotTypeConfig& robot) {
  CommandCheck check;
  // What no robot can apply (the check the radio emulator and the Python
  // module make too); the robot's own limits are applied below.
  if (auto fault = find_command_fault(raw, robot.wheels.size(), nullptr)) {
    check.problem = std::move(fault->detail);
    return check;
  }
  RobotCommand& c = check.command;
  c.mode = raw.mode == robot_command_t::MODE_WHEEL_SPEEDS      ? CommandMode::WheelSpeeds
           : raw.mode == robot_command_t::MODE_GLOBAL_VELOCITY ? CommandMode::GlobalVelocity
                                                               : CommandMode::LocalVelocity;
  Findings found;
  if (c.mode == CommandMode::WheelSpeeds) {
    for (double w : raw.wheel_speeds) {
      c.wheel_speeds.push_back(
          clamp_magnitude(w, robot.motor_max_speed, CommandLimit::WheelSpeed, "rad/s", found));
    }
  } else {
    const double speed = std::hypot(raw.vx, raw.vy);
    double scale = 1;
    if (speed > robot.max_speed) {
      scale = robot.max_speed / speed;
      found.note(CommandLimit::Speed,
                 "speed " + number(speed) + " m/s clamped to " + number(robot.max_speed));
    }
    c.vx = raw.vx * scale;
    c.vy = raw.vy * scale;
    c.omega = clamp_magnitude(raw.omega, robot.max_angular_speed, CommandLimit::AngularSpeed,
                              "rad/s", found);
  }

  if (raw.kick_speed < 0 || raw.chip_speed < 0) {
    found.note(CommandLimit::NegativeKick, "negative kick speed ignored");
  }
  c.kick_speed = std::max(0.0, raw.kick_speed);
  c.chip_speed = std::max(0.0, raw.chip_speed);
  c.kick_speed =
      clamp_magnitude(c.kick_speed, robot.kick_max_speed, CommandLimit::KickSpeed, "m/s", found);
  c.chip_speed =
      clamp_magnitude(c.chip_speed, robot.chip_max_speed, CommandLimit::ChipSpeed, "m/s", found);
  c.chip_angle = raw.chip_angle > 0 ? raw.chip_angle : robot.chip_default_angle;
  if (raw.chip_angle < 0) {
    found.note(CommandLimit::NegativeChipAngle, "negative chip angle replaced by the default");
  }
  c.chip_angle =
      clamp_magnitude(c.chip_angle, robot.chip_max_angle, CommandLimit::ChipAngle, "rad", found);
  c.dribbler_speed = clamp_magnitude(raw.dribbler_speed, robot.dribbler_max_speed,
                                     CommandLimit::DribblerSpeed, "rad/s", found);
  check.accepted = true;
  check.clamped = found.limits != 0;
  check.limits_hit = found.limits;
  check.problem = std::move(found.problems);
  if (check.problem.size() >= 2) check.problem.resize(check.problem.size() - 2);  // trailing "; "
  return check;
}

}  // namespace ubersim::physics
