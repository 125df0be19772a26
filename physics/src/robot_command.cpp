#include "ubersim/physics/robot_command.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace ubersim::physics {
namespace {

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

// Clamps |value| to limit, noting what it did (text only when needed: this
// runs for every command of every robot).
double clamp_magnitude(double value, double limit, const char* what, const char* unit,
                       std::string& problems, bool& clamped) {
  if (std::abs(value) <= limit) return value;
  problems +=
      std::string(what) + " " + number(value) + " " + unit + " clamped to " + number(limit) + "; ";
  clamped = true;
  return std::copysign(limit, value);
}

}  // namespace

CommandCheck check_command(const robot_command_t& raw, const RobotTypeConfig& robot) {
  CommandCheck check;
  const double values[] = {raw.vx,         raw.vy,         raw.omega,         raw.kick_speed,
                           raw.chip_speed, raw.chip_angle, raw.dribbler_speed};
  for (double v : values) {
    if (!std::isfinite(v)) {
      check.problem = "non-finite value in command";
      return check;
    }
  }
  RobotCommand& c = check.command;
  switch (raw.mode) {
    case robot_command_t::MODE_LOCAL_VELOCITY:
      c.mode = CommandMode::LocalVelocity;
      break;
    case robot_command_t::MODE_GLOBAL_VELOCITY:
      c.mode = CommandMode::GlobalVelocity;
      break;
    case robot_command_t::MODE_WHEEL_SPEEDS:
      c.mode = CommandMode::WheelSpeeds;
      break;
    default:
      check.problem = "unknown command mode " + std::to_string(raw.mode);
      return check;
  }
  std::string problems;
  bool clamped = false;
  if (c.mode == CommandMode::WheelSpeeds) {
    if (raw.num_wheels != static_cast<int>(robot.wheels.size()) ||
        raw.wheel_speeds.size() != robot.wheels.size()) {
      check.problem = "wheel-speed command for " + std::to_string(raw.num_wheels) +
                      " wheels, robot has " + std::to_string(robot.wheels.size());
      return check;
    }
    for (double w : raw.wheel_speeds) {
      if (!std::isfinite(w)) {
        check.problem = "non-finite wheel speed in command";
        return check;
      }
    }
    for (double w : raw.wheel_speeds) {
      c.wheel_speeds.push_back(
          clamp_magnitude(w, robot.motor_max_speed, "wheel speed", "rad/s", problems, clamped));
    }
  } else {
    const double speed = std::hypot(raw.vx, raw.vy);
    double scale = 1;
    if (speed > robot.max_speed) {
      scale = robot.max_speed / speed;
      problems += "speed " + number(speed) + " m/s clamped to " + number(robot.max_speed) + "; ";
      clamped = true;
    }
    c.vx = raw.vx * scale;
    c.vy = raw.vy * scale;
    c.omega = clamp_magnitude(raw.omega, robot.max_angular_speed, "angular speed", "rad/s",
                              problems, clamped);
  }

  if (raw.kick_speed < 0 || raw.chip_speed < 0) {
    problems += "negative kick speed ignored; ";
    clamped = true;
  }
  c.kick_speed = std::max(0.0, raw.kick_speed);
  c.chip_speed = std::max(0.0, raw.chip_speed);
  c.kick_speed =
      clamp_magnitude(c.kick_speed, robot.kick_max_speed, "kick speed", "m/s", problems, clamped);
  c.chip_speed =
      clamp_magnitude(c.chip_speed, robot.chip_max_speed, "chip speed", "m/s", problems, clamped);
  c.chip_angle = raw.chip_angle > 0 ? raw.chip_angle : robot.chip_default_angle;
  if (raw.chip_angle < 0) {
    problems += "negative chip angle replaced by the default; ";
    clamped = true;
  }
  c.chip_angle =
      clamp_magnitude(c.chip_angle, robot.chip_max_angle, "chip angle", "rad", problems, clamped);
  c.dribbler_speed = clamp_magnitude(raw.dribbler_speed, robot.dribbler_max_speed, "dribbler speed",
                                     "rad/s", problems, clamped);
  check.accepted = true;
  check.clamped = clamped;
  check.problem = problems;
  if (check.problem.size() >= 2) check.problem.resize(check.problem.size() - 2);  // trailing "; "
  return check;
}

}  // namespace ubersim::physics
