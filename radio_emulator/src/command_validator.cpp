#include "ubersim/radio/command_validator.hpp"

#include <cmath>
#include <set>
#include <ubersim/team_t.hpp>

namespace ubersim::radio {
namespace {

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

bool known_mode(std::int8_t mode) {
  return mode == robot_command_t::MODE_LOCAL_VELOCITY ||
         mode == robot_command_t::MODE_GLOBAL_VELOCITY ||
         mode == robot_command_t::MODE_WHEEL_SPEEDS;
}

}  // namespace

const char* problem_name(Problem problem) {
  switch (problem) {
    case Problem::NoSimTime:
      return "before any SIM_STATE";
    case Problem::UnknownTeam:
      return "unknown team";
    case Problem::TeamMismatch:
      return "team does not match channel";
    case Problem::UnknownMode:
      return "unknown mode";
    case Problem::NonFinite:
      return "NaN/Inf";
    case Problem::AbsurdValue:
      return "absurd value";
    case Problem::WheelCount:
      return "wrong wheel count";
    case Problem::DuplicateRobot:
      return "duplicate robot id";
    case Problem::OffField:
      return "robot not on the field";
  }
  return "?";
}

Validated validate_packet(const radio_packet_t& packet, Team channel_team,
                          const CommandLimits& limits, const RobotsOnField& robots) {
  Validated out;
  const int channel_team_code = static_cast<int>(channel_team);
  if (packet.team != team_t::YELLOW && packet.team != team_t::BLUE) {
    out.findings.push_back(
        {Problem::UnknownTeam, -1, "team field " + std::to_string(int{packet.team})});
    return out;
  }
  if (packet.team != channel_team_code) {
    out.findings.push_back({Problem::TeamMismatch, -1,
                            std::string("team field says ") +
                                team_name(static_cast<Team>(packet.team)) + " on the " +
                                team_name(channel_team) + " channel"});
    return out;
  }
  out.packet_ok = true;
  out.packet.team = packet.team;
  out.packet.sequence = packet.sequence;
  out.packet.t_sent = packet.t_sent;

  std::map<std::int32_t, int> entries_per_id;
  for (const auto& c : packet.commands) ++entries_per_id[c.robot_id];
  std::set<std::int32_t> duplicates_reported;

  for (const auto& command : packet.commands) {
    const std::int32_t id = command.robot_id;
    if (entries_per_id[id] > 1) {
      if (duplicates_reported.insert(id).second)
        out.findings.push_back({Problem::DuplicateRobot, id,
                                std::to_string(entries_per_id[id]) + " entries for one robot"});
      continue;
    }
    const auto robot = robots.find(id);
    if (robot == robots.end()) {
      out.findings.push_back({Problem::OffField, id, "no such robot on the field"});
      continue;
    }
    if (!known_mode(command.mode)) {
      out.findings.push_back({Problem::UnknownMode, id, "mode " + std::to_string(command.mode)});
      continue;
    }
    if (!all_finite(command)) {
      out.findings.push_back({Problem::NonFinite, id, "a field is NaN or infinite"});
      continue;
    }
    if (const std::string what = absurd_value(command, limits); !what.empty()) {
      out.findings.push_back({Problem::AbsurdValue, id, what});
      continue;
    }
    robot_command_t clean = command;
    if (command.mode == robot_command_t::MODE_WHEEL_SPEEDS) {
      const std::int32_t wheels = robot->second;
      if (command.num_wheels == 0 || (wheels > 0 && command.num_wheels != wheels)) {
        out.findings.push_back({Problem::WheelCount, id,
                                std::to_string(command.num_wheels) +
                                    " wheel speeds for a robot with " + std::to_string(wheels)});
        continue;
      }
    } else {
      clean.num_wheels = 0;
      clean.wheel_speeds.clear();
    }
    out.packet.commands.push_back(std::move(clean));
  }
  out.packet.num_commands = static_cast<std::int32_t>(out.packet.commands.size());
  return out;
}

}  // namespace ubersim::radio
