#pragma once
// Logging goes through spdlog. Verbosity follows the usual convention:
// default info, -v debug, -vv trace, -q warnings only, -qq errors only.
#include <chrono>
#include <map>
#include <string>

#include "ubersim/spdlog.hpp"

namespace ubersim {

void setup_logging(const std::string& process_name, int verbosity);

// For bad input that can arrive at any rate: counts every occurrence, logs the
// first at once and then at most once per `period` per key with the count since.
class ThrottledLog {
 public:
  explicit ThrottledLog(std::chrono::steady_clock::duration period = std::chrono::seconds(1))
      : period_(period) {}

  // Returns true when this occurrence was logged.
  bool warn(const std::string& key, const std::string& message);
  std::uint64_t count(const std::string& key) const;
  std::uint64_t total() const { return total_; }
  // "none", or every key with its count: "decode:SIM_COMMANDS=12 nan:robot=1",
  // for status replies that show what was dropped.
  std::string counts() const;

 private:
  struct Entry {
    std::uint64_t count = 0;
    std::uint64_t count_at_last_log = 0;
    std::chrono::steady_clock::time_point last_log{};
    bool logged = false;
  };
  std::chrono::steady_clock::duration period_;
  std::map<std::string, Entry> entries_;
  std::uint64_t total_ = 0;
};

}  // namespace ubersim
