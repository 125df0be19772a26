#pragma once
// Command-line parsing every ubersim process shares (CLI11): the options of
// ubersim/common_options.hpp taken the same way by every process, range checks
// that name their range, and one readable line for a bad command line.
#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "ubersim/common_options.hpp"

namespace ubersim {

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
