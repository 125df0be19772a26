#include "ubersim/dds_bridge/sample_checks.hpp"

#include <ubersim/team_t.hpp>

#include "ubersim/radio/command_validator.hpp"

namespace ubersim::dds {
namespace {

// Moves validator findings into an admission.
void record(Admission& admission, const std::vector<radio::Finding>& findings) {
  for (const auto& finding : findings) {
    std::string detail = radio::problem_name(finding.problem);
    if (finding.robot_id >= 0) detail += " (robot " + std::to_string(finding.robot_id) + ")";
    if (!finding.detail.empty()) detail += ": " + finding.detail;
    admission.findings.push_back({radio::problem_name(finding.problem), detail});
  }
}

// Runs the radio emulator's validator over a packet's commands. The bridge
// does not know which robots are on the field: every id in the packet counts
// as present with an unknown wheel count (0), so only the field-independent
// checks apply here.
Admission validate(radio_packet_t& packet, Team channel_team, const radio::CommandLimits& limits) {
  radio::RobotsOnField robots;
  for (const auto& command : packet.commands) robots[command.robot_id] = 0;
  radio::Validated validated = radio::validate_packet(packet, channel_team, limits, robots);
  Admission admission;
  record(admission, validated.findings);
  if (!validated.packet_ok) {
    admission.forward = false;
    return admission;
  }
  // A packet that had entries and lost them all carries nothing: dropped, as
  // the radio emulator drops it. A packet sent empty goes on as it came.
  if (validated.packet.commands.empty() && !packet.commands.empty()) {
    admission.forward = false;
    return admission;
  }
  admission.entries_removed = packet.commands.size() - validated.packet.commands.size();
  packet = std::move(validated.packet);
  return admission;
}

}  // namespace

Admission admit_radio(radio_packet_t& packet, Team channel_team,
                      const radio::CommandLimits& limits) {
  return validate(packet, channel_team, limits);
}

Admission admit_commands(sim_commands_t& commands, const radio::CommandLimits& limits) {
  // The commands go through the radio validator (a bad entry is removed, the
  // rest goes on); a non-finite number in the rest drops the whole message.
  radio_packet_t packet{};
  packet.commands = std::move(commands.commands);
  const std::string non_finite = non_finite_field(commands);
  commands.commands = std::move(packet.commands);
  if (!non_finite.empty()) {
    Admission admission;
    admission.forward = false;
    admission.findings.push_back({"NaN/Inf", non_finite + " is not finite"});
    return admission;
  }
  // The same checks as a radio packet of that team: wrap, validate, unwrap.
  packet.team = commands.team;
  packet.sequence = commands.sequence;
  packet.commands = std::move(commands.commands);
  packet.num_commands = static_cast<std::int32_t>(packet.commands.size());
  const Team team = commands.team == team_t::BLUE ? Team::Blue : Team::Yellow;
  Admission admission = validate(packet, team, limits);
  commands.commands = std::move(packet.commands);
  commands.num_commands = static_cast<std::int32_t>(commands.commands.size());
  return admission;
}

}  // namespace ubersim::dds
