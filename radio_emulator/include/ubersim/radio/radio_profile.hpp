#pragma once
// An emulator profile (config/radio/<name>.cfg): how one team's radio link
// behaves. Both directions are modelled: commands (control software -> robots)
// and feedback (robots -> control software).
#include <cstdint>
#include <string>

#include "ubersim/command_check.hpp"
#include "ubersim/config.hpp"

namespace ubersim::radio {

// One direction of the link: delay and loss.
struct LinkTiming {
  double latency = 0;         // s, fixed delay from transmission to reception
  double latency_jitter = 0;  // s, sigma of Gaussian noise on the latency
  double packet_loss = 0;     // probability a whole packet is lost
  double robot_loss = 0;  // probability one robot's entry is lost from a packet that got through
};

// Sanity limits of the radio's packet format (ubersim/command_check.hpp). A
// value beyond them is a bug in the sender (wrong units, uninitialised
// memory), so the robot's entry is dropped, not clamped. A robot's own limits
// (config/robots) are lower; physics clamps to those, as the robot's firmware
// does.
using CommandLimits = ubersim::CommandLimits;

struct RadioProfile {
  std::string name;
  double max_packet_rate = 0;  // Hz, packets the link transmits per second, 0 = unlimited
  LinkTiming command;          // control software -> robots
  double command_timeout = 0;  // s, a robot that hears nothing this long stops, 0 = never
  double feedback_rate = 0;    // Hz, feedback packets per second, 0 = no feedback
  LinkTiming feedback;         // robots -> control software
  CommandLimits limits;
  std::uint64_t seed = 0;  // default seed of the random streams (--seed overrides)
};

// Reads every key of a profile (and rejects any other). Throws ConfigError.
RadioProfile load_radio_profile(const ConfigFile& config, const std::string& name);
// `name` is a profile name (config/radio/<name>.cfg) or a path to a .cfg file.
RadioProfile load_radio_profile(const std::string& config_dir, const std::string& name);

}  // namespace ubersim::radio
