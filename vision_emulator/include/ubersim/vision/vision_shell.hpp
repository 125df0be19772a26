#pragma once
// The ubersim_vision program: a VisionEmulator (the core) and its VisionShell
// (vision_shell.cpp) on the process host (docs/design.md, "One shape for every
// program"). Subscribes SIM_STATE and SIM_GEOMETRY, publishes VISION (one
// vision_frame_t per camera frame, in sim time) and VISION_GEOMETRY (at start
// once the field is known, whenever it changes, and every GEOMETRY_PERIOD
// seconds of wall-clock time, so a control program that starts while physics
// is paused still gets it); SIM_VISION_SCHEDULE and SIM_TRUTH_DEMAND say which
// frames come when and which ground truth they need.
#include <cstdint>
#include <optional>
#include <string>

#include "ubersim/common_options.hpp"

namespace ubersim::vision {

struct VisionProcessOptions {
  CommonOptions common;
  std::string profile = "cmdragons02";
  std::optional<std::uint64_t> seed;  // overrides the profile's SEED
  std::string field;                  // geometry to use until SIM_GEOMETRY arrives ("" = none)
};

// Runs until SIGINT/SIGTERM; returns the process exit code. Throws
// ConfigError for a bad profile or field, std::runtime_error when LCM fails.
int run_vision_process(const VisionProcessOptions& options);

}  // namespace ubersim::vision
