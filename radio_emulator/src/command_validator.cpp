#include "ubersim/radio/command_validator.hpp"

#include <algorithm>
#include <set>
#include <ubersim/team_t.hpp>

namespace ubersim::radio {
namespace {

Problem problem_of(CommandFault fault) {
  switch (fault) {
    case CommandFault::UnknownMode:
      return Problem::UnknownMode;
    case CommandFault::NonFinite:
      return Problem::NonFinite;
    case CommandFault::AbsurdValue:
      return Problem::AbsurdValue;
    case CommandFault::WheelCount:
      return Problem::WheelCount;
  }
  return Problem::AbsurdValue;
}

// The checks of validate_packet; limits nullptr: no sanity limits.
Validated validate(const radio_packet_t& packet, Team channel_team, const CommandLimits* limits,
                   const RobotsOnField& robots) {
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
    const auto wheels = static_cast<std::size_t>(std::max(0, robot->second));
    if (auto fault = find_command_fault(command, wheels, limits)) {
      out.findings.push_back({problem_of(fault->fault), id, std::move(fault->detail)});
      continue;
    }
    robot_command_t clean = command;
    if (command.mode != robot_command_t::MODE_WHEEL_SPEEDS) {
      clean.num_wheels = 0;
      clean.wheel_speeds.clear();
    }
    out.packet.commands.push_back(std::move(clean));
  }
  out.packet.num_commands = static_cast<std::int32_t>(out.packet.commands.size());
  return out;
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
  return validate(packet, channel_team, &limits, robots);
}

Validated validate_packet(const radio_packet_t& packet, Team channel_team,
                          const RobotsOnField& robots) {
  return validate(packet, channel_team, nullptr, robots);
}

}  // namespace ubersim::radio
