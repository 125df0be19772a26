#pragma once
// ubersim_gc_link's shell (docs/design.md, "One shape for every program"): the
// GcLink core and the game controller's CI client on the process host. The
// command line (main.cpp) fills the options.
#include <string>

#include "ubersim/common_options.hpp"

namespace ubersim::gc_link {

struct GcLinkOptions {
  CommonOptions common;
  std::string game_controller;  // binary to start, or empty
  std::string gc_address;       // a GC already running in CI mode, or empty
  std::string gc_dir = "gc";    // the started GC's folder
  std::string game = "division_b";
  double game_length = 0;      // s, both halves; 0: the game config's
  double half_time = 5;        // s of break
  double tick_period = 0.025;  // s
  double timeout_s = 10;       // for physics, the GC's start and each answer
  std::string yellow_name = "Yellow", blue_name = "Blue";
  std::string yellow_defends = "negative";
  std::string events_file;
  bool keep_running = false;
};

// Runs the link until the game is over (0; not with keep_running), the game
// controller failed (1) or SIGINT/SIGTERM (0). Throws ConfigError for a bad
// game config, std::runtime_error when physics or the GC does not answer.
int run_gc_link(const GcLinkOptions& options);

}  // namespace ubersim::gc_link
