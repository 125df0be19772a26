#include "ubersim/channels.hpp"

#include <algorithm>
#include <stdexcept>

#include "ubersim/topics.hpp"

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

ChannelNames::ChannelNames(std::string prefix, std::map<std::string, std::string> overrides)
    : prefix_(std::move(prefix)), overrides_(std::move(overrides)) {
  for (const auto& [base, name] : overrides_) {
    const bool known = std::find(topics::kAllNames.begin(), topics::kAllNames.end(), base) !=
                       topics::kAllNames.end();
    if (!known) throw std::invalid_argument("no channel named '" + base + "' to override");
    if (name.empty()) throw std::invalid_argument("empty channel name for '" + base + "'");
  }
}

std::string ChannelNames::resolve(std::string_view base) const {
  if (auto found = overrides_.find(std::string(base)); found != overrides_.end())
    return found->second;
  return prefix_ + std::string(base);
}

std::pair<std::string, std::string> ChannelNames::parse_override(const std::string& text) {
  const auto equals = text.find('=');
  if (equals == std::string::npos || equals == 0 || equals + 1 == text.size()) {
    throw std::invalid_argument("expected BASE_NAME=CHANNEL, got '" + text + "'");
  }
  return {text.substr(0, equals), text.substr(equals + 1)};
}

}  // namespace ubersim
