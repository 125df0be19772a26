#include "ubersim/command_check.hpp"

#include <cmath>

namespace ubersim {
namespace {

bool known_mode(std::int8_t mode) {
  return mode == robot_command_t::MODE_LOCAL_VELOCITY ||
         mode == robot_command_t::MODE_GLOBAL_VELOCITY ||
         mode == robot_command_t::MODE_WHEEL_SPEEDS;
}

bool all_finite(const robot_command_t& c) {
  for (double v : {c.vx, c.vy, c.omega, c.kick_speed, c.chip_speed, c.chip_angle, c.dribbler_speed})
    if (!std::isfinite(v)) return false;
  if (c.mode == robot_command_t::MODE_WHEEL_SPEEDS)
    for (double w : c.wheel_speeds)
      if (!std::isfinite(w)) return false;
  return true;
}

// Empty when the values are sane, else what is wrong.
std::string absurd_value(const robot_command_t& c, const CommandLimits& limits) {
  const auto beyond = [](const char* what, double value, double limit, const char* unit) {
    return std::string(what) + " " + std::to_string(value) + " " + unit + " beyond the limit " +
           std::to_string(limit) + " " + unit;
  };
  if (c.mode == robot_command_t::MODE_WHEEL_SPEEDS) {
    for (double w : c.wheel_speeds)
      if (std::abs(w) > limits.wheel_speed)
        return beyond("wheel speed", w, limits.wheel_speed, "rad/s");
  } else {
    const double speed = std::hypot(c.vx, c.vy);
    if (speed > limits.speed) return beyond("speed", speed, limits.speed, "m/s");
    if (std::abs(c.omega) > limits.angular_speed)
      return beyond("angular speed", c.omega, limits.angular_speed, "rad/s");
  }
  if (c.kick_speed < 0 || c.kick_speed > limits.kick_speed)
    return beyond("kick speed", c.kick_speed, limits.kick_speed, "m/s") + " (or negative)";
  if (c.chip_speed < 0 || c.chip_speed > limits.kick_speed)
    return beyond("chip speed", c.chip_speed, limits.kick_speed, "m/s") + " (or negative)";
  if (c.chip_angle < 0 || c.chip_angle >= M_PI / 2)
    return "chip angle " + std::to_string(c.chip_angle) + " rad outside [0, pi/2)";
  if (std::abs(c.dribbler_speed) > limits.dribbler_speed)
    return beyond("dribbler speed", c.dribbler_speed, limits.dribbler_speed, "rad/s");
  return {};
}

bool wrong_wheel_count(const robot_command_t& c, std::size_t wheels) {
  const auto given = static_cast<std::size_t>(c.num_wheels);
  return c.num_wheels <= 0 || c.wheel_speeds.size() != given || (wheels > 0 && given != wheels);
}

}  // namespace

std::optional<CommandFaultFound> find_command_fault(const robot_command_t& command,
                                                    std::size_t wheels,
                                                    const CommandLimits* limits) {
  if (!known_mode(command.mode)) {
    return CommandFaultFound{CommandFault::UnknownMode, "mode " + std::to_string(command.mode)};
  }
  if (!all_finite(command)) {
    return CommandFaultFound{CommandFault::NonFinite, "a field is NaN or infinite"};
  }
  if (limits != nullptr) {
    if (std::string what = absurd_value(command, *limits); !what.empty()) {
      return CommandFaultFound{CommandFault::AbsurdValue, std::move(what)};
    }
  }
  if (command.mode == robot_command_t::MODE_WHEEL_SPEEDS && wrong_wheel_count(command, wheels)) {
    return CommandFaultFound{CommandFault::WheelCount, std::to_string(command.num_wheels) +
                                                           " wheel speeds for a robot with " +
                                                           std::to_string(wheels)};
  }
  return std::nullopt;
}

}  // namespace ubersim
