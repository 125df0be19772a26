#include "ubersim/logging.hpp"

#include <spdlog/sinks/stdout_color_sinks.h>

namespace ubersim {

void setup_logging(const std::string& process_name, int verbosity) {
  // Log to stderr so stdout stays free for a tool's real output.
  auto logger = spdlog::stderr_color_mt(process_name);
  logger->set_pattern("[%H:%M:%S.%e] [%n] [%^%l%$] %v");
  spdlog::level::level_enum level = spdlog::level::info;
  if (verbosity >= 2)
    level = spdlog::level::trace;
  else if (verbosity == 1)
    level = spdlog::level::debug;
  else if (verbosity == -1)
    level = spdlog::level::warn;
  else if (verbosity <= -2)
    level = spdlog::level::err;
  logger->set_level(level);
  logger->flush_on(spdlog::level::info);
  spdlog::set_default_logger(logger);
}

bool ThrottledLog::warn(const std::string& key, const std::string& message) {
  Entry& e = entries_[key];
  ++e.count;
  ++total_;
  const auto now = std::chrono::steady_clock::now();
  if (e.logged && now - e.last_log < period_) return false;
  const std::uint64_t since = e.count - e.count_at_last_log;
  if (e.logged && since > 1) {
    spdlog::warn("{} ({} times since last report, {} in all)", message, since, e.count);
  } else {
    spdlog::warn("{}", message);
  }
  e.logged = true;
  e.last_log = now;
  e.count_at_last_log = e.count;
  return true;
}

std::uint64_t ThrottledLog::count(const std::string& key) const {
  const auto found = entries_.find(key);
  return found == entries_.end() ? 0 : found->second.count;
}

std::string ThrottledLog::counts() const {
  std::string text;
  for (const auto& [key, entry] : entries_) {
    if (!text.empty()) text += ' ';
    text += key + "=" + std::to_string(entry.count);
  }
  return text.empty() ? "none" : text;
}

}  // namespace ubersim
