#pragma once
// What the bridge checks in a sample that came from DDS before it publishes it
// on LCM (a DDS peer is as untrusted as any LCM sender):
//  * radio packets (RADIO_<TEAM>) and SIM_COMMANDS go through the radio
//    emulator's own validator (ubersim_radio_lib, command_validator.hpp), so a
//    bad sample is treated exactly as the radio emulator treats a bad LCM
//    packet: wrong/unknown team drops the packet; a robot entry with NaN/Inf,
//    an absurd value or an unknown mode is removed (the rest goes on); a packet
//    left with no entry is dropped;
//  * every other type is dropped whole when any real number in it is NaN/Inf.
// Semantic checks (is that robot on the field, is that action known) stay
// with the receiving process, which has the context for them.
#include <cstddef>
#include <string>
#include <vector>

#include "ubersim/channels.hpp"
#include "ubersim/dds_bridge/convert.hpp"
#include "ubersim/radio/radio_profile.hpp"

namespace ubersim::dds {

struct Finding {
  std::string problem;  // short and fixed, for counting: "NaN/Inf", "absurd value", ...
  std::string detail;   // for the log
};

struct Admission {
  bool forward = true;              // false: drop the whole sample
  std::size_t entries_removed = 0;  // robot entries taken out of a packet that goes on
  std::vector<Finding> findings;
};

// non_finite_field(message): convert.hpp, generated from the .lcm files.
template <class Msg>
Admission admit(const Msg& message) {
  Admission admission;
  if (std::string field = non_finite_field(message); !field.empty()) {
    admission.forward = false;
    admission.findings.push_back({"NaN/Inf", field + " is not finite"});
  }
  return admission;
}

// The radio emulator's validator, robots' wheel counts unknown and every robot
// id accepted (the bridge does not know the field; the radio emulator
// downstream does). `packet` is replaced by what may go on.
Admission admit_radio(radio_packet_t& packet, Team channel_team,
                      const radio::CommandLimits& limits);
Admission admit_commands(sim_commands_t& commands, const radio::CommandLimits& limits);

}  // namespace ubersim::dds
