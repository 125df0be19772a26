#pragma once
// Reading what lcm-logger recorded, channel by channel: sync mode promises the
// same bytes on each channel, in the same order, from two runs alike
// (the interleaving of channels follows the wall clock and may differ).
#include <map>
#include <string>
#include <vector>

#include "ubersim/bounded_decode.hpp"

namespace e2e {

using ChannelLog = std::vector<std::vector<unsigned char>>;

// Every message of every channel in `path`, in the order recorded. Throws
// std::runtime_error when the log cannot be read.
std::map<std::string, ChannelLog> read_log_by_channel(const std::string& path);

// "" when equal, else where the two first differ.
std::string compare_channel(const ChannelLog& a, const ChannelLog& b);

// The channels whose content sync mode makes reproducible.
const std::vector<std::string>& reproducible_channels();

// SIM_COMMANDS carries both teams, interleaved as their answers came in: each
// team's own sequence (team 0 yellow, 1 blue) is what is reproducible.
ChannelLog team_only(const ChannelLog& sim_commands, int team);

// Every message of a channel's log that decodes as Msg, in order.
template <class Msg>
std::vector<Msg> decode_all(const ChannelLog& log) {
  std::vector<Msg> out;
  for (const auto& bytes : log) {
    Msg message;
    if (ubersim::decode_bounded(bytes.data(), bytes.size(), message)) out.push_back(message);
  }
  return out;
}

}  // namespace e2e
