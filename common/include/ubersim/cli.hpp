#pragma once
// Command-line options every ubersim process shares (CLI11), so that every
// process takes an LCM URL, a channel prefix, channel overrides, a config
// folder and -v/-q the same way.
#include <CLI/CLI.hpp>
#include <optional>
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

void add_common_options(CLI::App& app, CommonOptions& options);

// Range checks for numeric options. CLI11's own (CLI::Range, NonNegativeNumber,
// PositiveNumber) print their bounds with std::to_string, so an open side shows
// up as the largest double, 300 digits long; these name the range in plain
// numbers: "--speed: -5 is not in [0, 1000]", "... is not at least 0".
CLI::Validator in_range(double min, double max);
CLI::Validator at_least(double min);
CLI::Validator greater_than(double min);
// For options held in an unsigned integer (seeds): CLI11 itself would take
// "-5" and wrap it to 18446744073709551611; this names what was expected.
CLI::Validator whole_number();

// Parses the command line (CLI11_PARSE's job) and says whether to stop:
// nothing to run on; 0 after --help or --version (printed on stdout); 2 after
// a bad command line, which is told on stderr in one line, the program's name
// first (a launcher shows it as it is).
std::optional<int> parse_command_line(CLI::App& app, int argc, const char* const* argv);
// The one line parse_command_line prints for a bad command line, without its
// trailing newline: control characters replaced, cut to a readable length.
std::string command_line_error(const std::string& program, const CLI::ParseError& error);

}  // namespace ubersim
