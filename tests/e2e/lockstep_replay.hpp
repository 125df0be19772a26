#pragma once
// Replays the radio packets of a recorded LCM log against physics in lockstep,
// with the vision and radio emulators, and returns every VISION frame they
// produced. Each packet is published at its recorded sim time (its t_sent, the
// capture time of the frame the team acted on, plus a fixed reaction time),
// and the driver waits for the radio emulator to forward it before stepping on,
// so the run does not depend on how fast the machine is.
#include <cstdint>
#include <string>
#include <vector>

#include "e2e_support.hpp"

namespace e2e {

struct ReplayResult {
  std::vector<std::vector<uint8_t>> frames;  // encoded VISION frames in order
  int packets_replayed = 0;
  int packets_not_forwarded = 0;
};

ReplayResult replay_in_lockstep(const std::string& log_path, double until_sim_time,
                                const TempDir& dir, const std::string& run_name);

}  // namespace e2e
