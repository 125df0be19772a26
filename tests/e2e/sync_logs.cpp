#include "sync_logs.hpp"

#include <lcm/lcm-cpp.hpp>
#include <stdexcept>
#include <ubersim/sim_commands_t.hpp>

#include "ubersim/bounded_decode.hpp"

namespace e2e {

std::map<std::string, ChannelLog> read_log_by_channel(const std::string& path) {
  lcm::LogFile log(path, "r");
  if (!log.good()) throw std::runtime_error("cannot read the log " + path);
  std::map<std::string, ChannelLog> channels;
  while (const lcm::LogEvent* event = log.readNextEvent()) {
    const auto* data = static_cast<const unsigned char*>(event->data);
    channels[event->channel].emplace_back(data, data + event->datalen);
  }
  return channels;
}

std::string compare_channel(const ChannelLog& a, const ChannelLog& b) {
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) {
    if (a[i] != b[i]) return "message " + std::to_string(i) + " differs";
  }
  if (a.size() != b.size()) {
    return std::to_string(a.size()) + " against " + std::to_string(b.size()) + " messages";
  }
  return "";
}

const std::vector<std::string>& reproducible_channels() {
  static const std::vector<std::string> channels{
      "VISION",   "RADIO_YELLOW", "RADIO_BLUE", "RADIO_FEEDBACK_YELLOW", "RADIO_FEEDBACK_BLUE",
      "SIM_STATE"};
  return channels;
}

ChannelLog team_only(const ChannelLog& sim_commands, int team) {
  ChannelLog out;
  for (const auto& bytes : sim_commands) {
    ubersim::sim_commands_t m;
    if (ubersim::decode_bounded(bytes.data(), bytes.size(), m) && m.team == team) {
      out.push_back(bytes);
    }
  }
  return out;
}

}  // namespace e2e
