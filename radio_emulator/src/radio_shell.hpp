#pragma once
// ubersim_radio's shell (docs/design.md, "One shape for every program"): the
// RadioEmulator core, in sync mode its SyncDriver, on the process host. The
// command line (main.cpp) fills the options.
#include <cstdint>
#include <optional>
#include <string>

#include "ubersim/common_options.hpp"
#include "ubersim/radio/sync_driver.hpp"

namespace ubersim::radio {

struct RadioOptions {
  CommonOptions common;
  std::string profile = "cmdragons02";
  std::string yellow_profile;  // overrides `profile` for one team
  std::string blue_profile;
  std::optional<std::uint64_t> seed;  // overrides the profiles' SEED
  bool sync = false;
  SyncOptions sync_options;
};

// Runs until SIGINT/SIGTERM (0) or, with --sync-strict, a dropped client (1).
// Throws ConfigError for a bad profile, std::runtime_error when LCM fails.
int run_radio(const RadioOptions& options);

}  // namespace ubersim::radio
