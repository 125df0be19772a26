#pragma once
// How a process names its LCM channels: a prefix ("SIM2_") lets several
// simulations share one network; per-channel overrides ("VISION=CAM") let a
// process listen where an existing stack already publishes. The channels
// themselves, their base names and message types, are the typed topics
// (topics.hpp).
#include <array>
#include <map>
#include <string>
#include <string_view>
#include <utility>

namespace ubersim {

enum class Team : int { Yellow = 0, Blue = 1 };
inline constexpr std::array<Team, 2> kTeams{Team::Yellow, Team::Blue};
const char* team_name(Team team);                      // "yellow" / "blue"
std::string robot_name(Team team, int id);             // "yellow 3", for messages
bool parse_team(const std::string& text, Team& team);  // accepts yellow/blue/y/b/0/1

class ChannelNames {
 public:
  ChannelNames() = default;
  // Throws std::invalid_argument for an override of a channel that does not exist.
  ChannelNames(std::string prefix, std::map<std::string, std::string> overrides);

  // The channel a base name (a topic's, topics.hpp) has in this process: its
  // override, or the prefix and the base name. Reach it through a topic:
  // channel_name(channels, topics::kSimState).
  std::string resolve(std::string_view base) const;

  // Parses "BASE_NAME=CHANNEL" as given on a command line.
  static std::pair<std::string, std::string> parse_override(const std::string& text);

 private:
  std::string prefix_;
  std::map<std::string, std::string> overrides_;
};

}  // namespace ubersim
