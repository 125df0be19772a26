#include "ubersim/channels.hpp"

#include <stdexcept>

namespace ubersim {

const char* team_name(Team team) {
  return team == Team::Yellow ? "yellow" : "blue";
}

std::string robot_name(Team team, int id) {
  return std::string(team_name(team)) + " " + std::to_string(id);
}

bool parse_team(const std::string& text, Team& team) {
  if (text == "yellow" || text == "YELLOW" || text == "y" || text == "0") {
    team = Team::Yellow;
    return true;
  }
  if (text == "blue" || text == "BLUE" || text == "b" || text == "1") {
    team = Team::Blue;
    return true;
  }
  return false;
}

const char* base_channel_name(Channel channel) {
  switch (channel) {
    case Channel::Vision:
      return "VISION";
    case Channel::VisionGeometry:
      return "VISION_GEOMETRY";
    case Channel::RadioYellow:
      return "RADIO_YELLOW";
    case Channel::RadioBlue:
      return "RADIO_BLUE";
    case Channel::RadioFeedbackYellow:
      return "RADIO_FEEDBACK_YELLOW";
    case Channel::RadioFeedbackBlue:
      return "RADIO_FEEDBACK_BLUE";
    case Channel::SimCommands:
      return "SIM_COMMANDS";
    case Channel::SimState:
      return "SIM_STATE";
    case Channel::SimControl:
      return "SIM_CONTROL";
    case Channel::SimControlAck:
      return "SIM_CONTROL_ACK";
    case Channel::SimGeometry:
      return "SIM_GEOMETRY";
  }
  throw std::invalid_argument("unknown channel");
}

ChannelNames::ChannelNames(std::string prefix, std::map<std::string, std::string> overrides)
    : prefix_(std::move(prefix)), overrides_(std::move(overrides)) {
  for (const auto& [base, name] : overrides_) {
    bool known = false;
    for (const char* extra : kExtraChannels) known = known || base == extra;
    for (Channel channel : kAllChannels) known = known || base == base_channel_name(channel);
    if (!known) throw std::invalid_argument("no channel named '" + base + "' to override");
    if (name.empty()) throw std::invalid_argument("empty channel name for '" + base + "'");
  }
}

std::string ChannelNames::operator()(Channel channel) const {
  const std::string base = base_channel_name(channel);
  if (auto found = overrides_.find(base); found != overrides_.end()) return found->second;
  return prefix_ + base;
}

std::string ChannelNames::radio(Team team) const {
  return (*this)(team == Team::Yellow ? Channel::RadioYellow : Channel::RadioBlue);
}

std::string ChannelNames::radio_feedback(Team team) const {
  return (*this)(team == Team::Yellow ? Channel::RadioFeedbackYellow : Channel::RadioFeedbackBlue);
}

std::string ChannelNames::extra(const char* base) const {
  if (auto found = overrides_.find(base); found != overrides_.end()) return found->second;
  return prefix_ + base;
}

std::pair<std::string, std::string> ChannelNames::parse_override(const std::string& text) {
  const auto equals = text.find('=');
  if (equals == std::string::npos || equals == 0 || equals + 1 == text.size()) {
    throw std::invalid_argument("expected BASE_NAME=CHANNEL, got '" + text + "'");
  }
  return {text.substr(0, equals), text.substr(equals + 1)};
}

}  // namespace ubersim
