#pragma once
// A bridge config (config/dds_bridge/<name>.cfg): which LCM channels cross to
// DDS, in which direction, under which topic name.
//
//   TOPIC_PREFIX = rt/ubersim/      # DDS topic = prefix + topic (ROS 2: "rt/" + ROS name)
//   RADIO_LIMITS = cmdragons02      # radio profile whose LIMIT_* keys check radio samples
//   VISION = lcm_to_dds [topic]     # one key per channel, by its base name;
//   RADIO_YELLOW = dds_to_lcm       # direction lcm_to_dds, dds_to_lcm, both or off;
//                                   # topic defaults to the base name in lower case
//
// A channel with no key is not bridged. Any other key is an error.
#include <string>
#include <string_view>
#include <vector>

#include "ubersim/config.hpp"
#include "ubersim/topics.hpp"

namespace ubersim::dds {

enum class Direction { Off, LcmToDds, DdsToLcm, Both };
const char* direction_name(Direction direction);  // as written in the config
bool carries_lcm_to_dds(Direction direction);
bool carries_dds_to_lcm(Direction direction);

struct Route {
  std::string_view channel;  // the topic's base name (bridged_topics.hpp)
  Direction direction = Direction::Off;
  std::string topic;  // full DDS topic name, prefix included
};

struct BridgeConfig {
  std::string name;
  std::string topic_prefix;
  std::string radio_limits;   // radio profile name (config/radio/<name>.cfg)
  std::vector<Route> routes;  // channels that are bridged, in kBridgedTopics order

  const Route* find(std::string_view channel) const;  // nullptr when not bridged
  template <class Msg>
  const Route* find(const Topic<Msg>& topic) const {
    return find(topic.name);
  }
};

// "vision" for VISION, "radio_yellow" for RADIO_YELLOW ...
std::string default_topic(std::string_view channel);

// Reads every key (and rejects any other). Throws ConfigError naming file and line.
BridgeConfig load_bridge_config(const ConfigFile& config, const std::string& name);
// `name` is a config name (config/dds_bridge/<name>.cfg) or a path to a .cfg file.
BridgeConfig load_bridge_config(const std::string& config_dir, const std::string& name);

}  // namespace ubersim::dds
