#pragma once
// The options every ubersim process shares (an LCM URL, a channel prefix,
// channel overrides, a config folder, -v/-q), without the command-line parser:
// a process's options struct holds them, and only the file that parses the
// command line includes ubersim/cli.hpp (CLI11 costs seconds of compile time
// in every file that includes it).
#include <string>
#include <vector>

#include "ubersim/channels.hpp"

namespace ubersim {

// LCM_DEFAULT_URL if set, else LCM's own default (ttl=0: nothing leaves the host).
std::string default_lcm_url();
// Adds recv_buf_size to a udpm:// URL that has none: LCM 1.3.1 leaves Linux at
// the ~208 KB kernel default, which drops bursts of SIM_STATE.
std::string with_receive_buffer(const std::string& url);

struct CommonOptions {
  std::string lcm_url = default_lcm_url();
  std::string channel_prefix;
  std::vector<std::string> channel_overrides;  // "BASE=NAME"
  std::string config_dir;
  int verbose = 0;
  int quiet = 0;

  int verbosity() const { return verbose - quiet; }
  ChannelNames channels() const;    // throws std::invalid_argument on a bad override
  std::string config_root() const;  // config_dir or the built-in default
};

}  // namespace ubersim
