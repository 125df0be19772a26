#include "ubersim/cli.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

#include "ubersim/config_paths.hpp"

namespace ubersim {

std::string default_lcm_url() {
  if (const char* env = std::getenv("LCM_DEFAULT_URL"); env && *env) return env;
  return "udpm://239.255.76.67:7667?ttl=0";
}

std::string with_receive_buffer(const std::string& url) {
  if (url.rfind("udpm://", 0) != 0 || url.find("recv_buf_size") != std::string::npos) return url;
  return url + (url.find('?') == std::string::npos ? "?" : "&") + "recv_buf_size=4194304";
}

ChannelNames CommonOptions::channels() const {
  std::map<std::string, std::string> overrides;
  for (const auto& text : channel_overrides) overrides.insert(ChannelNames::parse_override(text));
  return ChannelNames(channel_prefix, overrides);
}

std::string CommonOptions::config_root() const {
  return config_dir.empty() ? default_config_dir().string() : config_dir;
}

void add_common_options(CLI::App& app, CommonOptions& options) {
  app.add_option("-l,--lcm-url", options.lcm_url, "LCM URL (default: $LCM_DEFAULT_URL or LCM's)")
      ->capture_default_str();
  app.add_option("--channel-prefix", options.channel_prefix,
                 "prefix for every channel name, to run several simulations side by side");
  app.add_option("--channel", options.channel_overrides,
                 "rename one channel, e.g. --channel VISION=CAM_VISION (repeatable)");
  app.add_option("--config-dir", options.config_dir, "folder with fields/, robots/, ... configs")
      ->check(CLI::ExistingDirectory);
  app.add_flag("-v,--verbose", options.verbose, "more log output (-vv for trace)");
  app.add_flag("-q,--quiet", options.quiet, "less log output (-qq for errors only)");
}

namespace {

// A value is echoed back as typed, but a pasted page of text makes no
// readable error line.
constexpr std::size_t kMaxEchoedValue = 40;
// The whole error line: what fits a terminal without wrapping twice.
constexpr std::size_t kMaxErrorLine = 200;

// Shortest plain form: 1000, 0.01, 65535 (never 1e+03, never 300 digits).
std::string plain_number(double value) {
  std::ostringstream out;
  out << std::setprecision(15) << value;
  return out.str();
}

// Printable ASCII only (a value may hold terminal escapes), cut to `limit`.
std::string printable(const std::string& text, std::size_t limit) {
  std::string out;
  for (const char c : text) {
    if (c == '\n' || c == '\t') {
      out += ' ';
    } else {
      out += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
    }
  }
  if (out.size() > limit) out = out.substr(0, limit - 3) + "...";
  return out;
}

std::optional<double> finite_number(const std::string& text) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) return std::nullopt;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

// `description` shows in --help after the option's type (FLOAT:[0, 1000]);
// `wanted` completes "<value> is not ..." in the error.
CLI::Validator number_check(const std::string& description, const std::string& wanted,
                            std::function<bool(double)> accepts) {
  return CLI::Validator(
      [wanted, accepts](std::string& input) -> std::string {
        const auto value = finite_number(input);
        if (!value) return "'" + printable(input, kMaxEchoedValue) + "' is not a number";
        if (!accepts(*value)) return printable(input, kMaxEchoedValue) + " is not " + wanted;
        return {};
      },
      description);
}

}  // namespace

CLI::Validator in_range(double min, double max) {
  const std::string range = "[" + plain_number(min) + ", " + plain_number(max) + "]";
  return number_check(range, "in " + range, [=](double v) { return v >= min && v <= max; });
}

CLI::Validator at_least(double min) {
  return number_check(">= " + plain_number(min), "at least " + plain_number(min),
                      [=](double v) { return v >= min; });
}

CLI::Validator greater_than(double min) {
  return number_check("> " + plain_number(min), "greater than " + plain_number(min),
                      [=](double v) { return v > min; });
}

CLI::Validator whole_number() {
  return CLI::Validator(
      [](std::string& input) -> std::string {
        const bool digits_only =
            !input.empty() && std::all_of(input.begin(), input.end(),
                                          [](unsigned char c) { return std::isdigit(c) != 0; });
        errno = 0;
        if (digits_only) (void)std::strtoull(input.c_str(), nullptr, 10);
        if (!digits_only || errno == ERANGE) {
          return "'" + printable(input, kMaxEchoedValue) +
                 "' is not a whole number (0 or more, below 2^64)";
        }
        return {};
      },
      "0 or more");
}

std::string command_line_error(const std::string& program, const CLI::ParseError& error) {
  const std::string prefix = printable(program, kMaxEchoedValue) + ": ";
  const std::string hint = " (see --help)";
  const std::size_t room = kMaxErrorLine - prefix.size() - hint.size();  // >= 200 - 43 - 13
  return prefix + printable(error.what(), room) + hint;
}

std::optional<int> parse_command_line(CLI::App& app, int argc, const char* const* argv) {
  try {
    app.parse(argc, argv);
    return std::nullopt;
  } catch (const CLI::Success& done) {
    return app.exit(done);  // --help, --help-all, --version: printed, exit 0
  } catch (const CLI::RuntimeError& stop) {
    return app.exit(stop);  // a callback chose its own exit code
  } catch (const CLI::ParseError& error) {
    // CLI11 would answer 105, 106 ... and a second line; one exit code for
    // "wrong command line" lets scripts and launch.sh tell it from a crash.
    const std::string path = argc > 0 ? argv[0] : "ubersim";
    const std::string program = path.substr(path.find_last_of('/') + 1);
    std::cerr << command_line_error(program, error) << std::endl;
    return 2;
  }
}

}  // namespace ubersim
