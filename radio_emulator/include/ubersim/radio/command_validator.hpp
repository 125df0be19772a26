#pragma once
// Checks a radio packet from a team's control software before it may go on to
// the link. Nothing bad is forwarded as it came: a packet that cannot be
// trusted as a whole is dropped; a robot entry that is bad is removed, and that
// robot keeps its previous command, as it would if the entry had been lost.
//
//   whole packet dropped:  team field not a team, team field not the channel's team
//   entry removed:         unknown mode, NaN/Inf anywhere, a value beyond the
//                          profile's sanity limits, negative kick/chip speed,
//                          chip angle outside [0, pi/2), wheel-speed mode with a
//                          wheel count that is not the robot's, a robot id given
//                          twice (every entry of it: which one was meant?), a
//                          robot that is not on the field
//   cleaned:               wheel_speeds of a velocity-mode entry (ignored by
//                          the robot, so removed rather than passed on unchecked)
//
// What is wrong with one entry's values is found by the check every part
// shares (ubersim/command_check.hpp); this adds what only a packet has: its
// team, one entry per robot, robots on the field.
#include <cstdint>
#include <map>
#include <string>
#include <ubersim/radio_packet_t.hpp>
#include <vector>

#include "ubersim/channels.hpp"
#include "ubersim/radio/radio_profile.hpp"

namespace ubersim::radio {

enum class Problem {
  NoSimTime,       // a packet before the first SIM_STATE: no sim time to stamp it with
  UnknownTeam,     // team field is neither YELLOW nor BLUE
  TeamMismatch,    // team field names the other team than the channel it came on
  UnknownMode,     // robot_command_t.mode is none of MODE_*
  NonFinite,       // NaN or Inf in a field
  AbsurdValue,     // beyond the sanity limits, or a negative kick speed, or a bad chip angle
  WheelCount,      // wheel-speed mode with the wrong number of wheels
  DuplicateRobot,  // the same robot id twice in one packet
  OffField,        // a robot of this team that is not on the field
};
inline constexpr int kProblemCount = 9;
const char* problem_name(Problem problem);  // short, for logs and reports

struct Finding {
  Problem problem;
  std::int32_t robot_id = -1;  // -1 when the whole packet is concerned
  std::string detail;
};

// robot id -> wheel count (0 when unknown), for the robots of one team on the field.
using RobotsOnField = std::map<std::int32_t, std::int32_t>;

struct Validated {
  bool packet_ok = false;  // false: drop the whole packet
  radio_packet_t packet;   // the entries that passed (team set to the channel's)
  std::vector<Finding> findings;
};

Validated validate_packet(const radio_packet_t& packet, Team channel_team,
                          const CommandLimits& limits, const RobotsOnField& robots);
// The same checks without sanity limits (values are then left to physics,
// which clamps them to the robot's own): the Python module's, which raises on
// what no radio forwards and leaves the limits to an emulated radio.
Validated validate_packet(const radio_packet_t& packet, Team channel_team,
                          const RobotsOnField& robots);

}  // namespace ubersim::radio
