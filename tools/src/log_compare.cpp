// ubersim_log_compare: whether two lcm-logger logs hold the same messages,
// channel by channel (the bytes, in order; not the wall-clock time stamps nor
// how channels interleave). Sync mode promises this for two runs with the same
// scenario, profiles and seeds (docs/sync.md). Exit 0 when every channel
// compared is the same, 1 when one differs, 2 on a usage or file error.
#include <CLI/CLI.hpp>
#include <iostream>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <regex>
#include <string>
#include <vector>

#include "ubersim/cli.hpp"
#include "ubersim/process_main.hpp"

namespace {

using Messages = std::vector<std::vector<unsigned char>>;

std::map<std::string, Messages> read_log(const std::string& path, const std::regex& channels) {
  lcm::LogFile log(path, "r");
  if (!log.good()) throw std::runtime_error("cannot read the log '" + path + "'");
  std::map<std::string, Messages> out;
  while (const lcm::LogEvent* event = log.readNextEvent()) {
    if (!std::regex_match(event->channel, channels)) continue;
    const auto* data = static_cast<const unsigned char*>(event->data);
    out[event->channel].emplace_back(data, data + event->datalen);
  }
  return out;
}

int parse_and_run(int argc, char** argv) {
  CLI::App app{"compare two LCM logs channel by channel (message bytes, in order)"};
  std::string first, second, pattern = ".*";
  app.add_option("first", first, "an lcm-logger log")->required();
  app.add_option("second", second, "another")->required();
  app.add_option("--channels", pattern, "regular expression of the channels to compare")
      ->capture_default_str();
  if (const auto stop = ubersim::parse_command_line(app, argc, argv)) return *stop;
  try {
    const std::regex channels(pattern);
    const auto a = read_log(first, channels);
    const auto b = read_log(second, channels);
    std::map<std::string, bool> names;
    for (const auto& [name, m] : a) names[name] = true;
    for (const auto& [name, m] : b) names[name] = true;
    bool same = true;
    for (const auto& [name, unused] : names) {
      static const Messages none;
      const Messages& x = a.count(name) ? a.at(name) : none;
      const Messages& y = b.count(name) ? b.at(name) : none;
      std::size_t i = 0;
      while (i < x.size() && i < y.size() && x[i] == y[i]) ++i;
      if (i == x.size() && i == y.size()) {
        std::cout << name << ": same (" << x.size() << " messages)\n";
        continue;
      }
      same = false;
      std::cout << name << ": DIFFERENT from message " << i << " (" << x.size() << " against "
                << y.size() << " messages)\n";
    }
    return same ? 0 : 1;
  } catch (const std::exception& error) {
    std::cerr << "ubersim_log_compare: " << error.what() << "\n";
    return 2;
  }
}

}  // namespace

int main(int argc, char** argv) {
  return ubersim::run_main("ubersim_log_compare", [&] { return parse_and_run(argc, argv); });
}
