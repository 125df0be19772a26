#pragma once
// ubersim_ssl_bridge's shell (docs/design.md, "One shape for every program"):
// the SslBridge, and with --grsim-port the GrsimPort, on the process host.
// The command line (main.cpp) fills the options.
#include <string>
#include <utility>
#include <vector>

#include "ubersim/common_options.hpp"
#include "ubersim/ssl_bridge/bridge.hpp"
#include "ubersim/ssl_bridge/grsim_port.hpp"

namespace ubersim::ssl {

// The program's command line: the bridge's own options and what its shell
// needs besides.
struct SslBridgeOptions {
  CommonOptions common;
  BridgeOptions bridge;
  GrsimOptions grsim;
  std::string robot_type = "omni4_ssl";
  std::string ball = "ssl_golf_ball";
  std::vector<std::pair<std::string, std::string>> team_commands;   // --team-command
  std::vector<std::pair<std::string, std::string>> team_protocols;  // --team-protocol
  double team_grace = 2.0;
  double team_charge_us = 1.0;       // --team-charge-us
  double team_yield_after_ms = 1.0;  // --team-yield-after-ms
};

// Bridges until SIGINT/SIGTERM (0). Fills in what `options.bridge` takes from
// the robot and ball configs first. Throws ConfigError for a bad config,
// std::runtime_error when a socket or LCM fails.
int run_ssl_bridge(SslBridgeOptions& options);

}  // namespace ubersim::ssl
