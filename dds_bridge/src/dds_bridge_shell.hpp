#pragma once
// ubersim_dds_bridge's shell (docs/design.md, "One shape for every program"):
// the dds::Bridge on the process host. The command line (main.cpp) fills the
// options.
#include <string>

#include "ubersim/common_options.hpp"

namespace ubersim::dds {

struct DdsBridgeOptions {
  CommonOptions common;
  int domain = 0;
  bool network = false;
  std::string config = "default";
  double truth_rate = 0;  // Hz of sim time; 0: every step
};

// Bridges until SIGINT/SIGTERM (0). Throws ConfigError for a bad config or
// radio profile, DdsError when Cyclone fails, std::runtime_error when LCM does.
int run_dds_bridge(const DdsBridgeOptions& options);

}  // namespace ubersim::dds
