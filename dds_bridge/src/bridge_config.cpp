#include "ubersim/dds_bridge/bridge_config.hpp"

#include <algorithm>
#include <cctype>
#include <set>

#include "ubersim/config_paths.hpp"
#include "ubersim/dds_bridge/bridged_topics.hpp"

namespace ubersim::dds {
namespace {

constexpr const char* kTopicPrefixKey = "TOPIC_PREFIX";
constexpr const char* kRadioLimitsKey = "RADIO_LIMITS";

Direction parse_direction(const ConfigFile& config, const std::string& key,
                          const std::string& text) {
  for (Direction d : {Direction::Off, Direction::LcmToDds, Direction::DdsToLcm, Direction::Both}) {
    if (text == direction_name(d)) return d;
  }
  config.fail(key, "direction '" + text + "': expected lcm_to_dds, dds_to_lcm, both or off");
}

// DDS topic names: ROS 2 allows letters, digits, '_' and '/'; so do we.
bool valid_topic(const std::string& topic) {
  if (topic.empty()) return false;
  return std::all_of(topic.begin(), topic.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '/';
  });
}

}  // namespace

const char* direction_name(Direction direction) {
  switch (direction) {
    case Direction::Off:
      return "off";
    case Direction::LcmToDds:
      return "lcm_to_dds";
    case Direction::DdsToLcm:
      return "dds_to_lcm";
    case Direction::Both:
      return "both";
  }
  return "?";
}

bool carries_lcm_to_dds(Direction direction) {
  return direction == Direction::LcmToDds || direction == Direction::Both;
}

bool carries_dds_to_lcm(Direction direction) {
  return direction == Direction::DdsToLcm || direction == Direction::Both;
}

const Route* BridgeConfig::find(std::string_view channel) const {
  for (const Route& route : routes)
    if (route.channel == channel) return &route;
  return nullptr;
}

std::string default_topic(std::string_view channel) {
  std::string topic(channel);
  std::transform(topic.begin(), topic.end(), topic.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return topic;
}

BridgeConfig load_bridge_config(const ConfigFile& config, const std::string& name) {
  BridgeConfig out;
  out.name = name;
  out.topic_prefix = config.string(kTopicPrefixKey, "");
  if (!out.topic_prefix.empty() && !valid_topic(out.topic_prefix))
    config.fail(kTopicPrefixKey,
                "topic prefix '" + out.topic_prefix + "': letters, digits, '_' and '/' only");
  out.radio_limits = config.string(kRadioLimitsKey, "cmdragons02");

  std::set<std::string> known{kTopicPrefixKey, kRadioLimitsKey};
  for (const std::string_view channel : kBridgedChannels) {
    const std::string key(channel);
    known.insert(key);
    if (!config.has(key)) continue;
    const std::vector<std::string> values = config.strings(key);
    if (values.size() > 2) config.fail(key, "expected a direction and at most one topic name");
    Route route;
    route.channel = channel;
    route.direction = parse_direction(config, key, values[0]);
    const std::string topic = values.size() == 2 ? values[1] : default_topic(channel);
    if (!valid_topic(topic))
      config.fail(key, "topic '" + topic + "': letters, digits, '_' and '/' only");
    route.topic = out.topic_prefix + topic;
    if (route.direction != Direction::Off) out.routes.push_back(route);
  }
  for (const std::string& key : config.keys()) {
    if (known.count(key) == 0) {
      std::string channels;
      for (const std::string_view channel : kBridgedChannels)
        channels += " " + std::string(channel);
      config.fail(key, "unknown key; expected TOPIC_PREFIX, RADIO_LIMITS or a channel:" + channels);
    }
  }
  std::set<std::string> topics;
  for (const Route& route : out.routes) {
    if (!topics.insert(route.topic).second)
      config.fail(std::string(route.channel),
                  "topic '" + route.topic + "' is used by another channel");
  }
  config.require_all_used();
  return out;
}

BridgeConfig load_bridge_config(const std::string& config_dir, const std::string& name) {
  const auto path = resolve_config(config_dir, "dds_bridge", name);
  return load_bridge_config(ConfigFile::load(path), name);
}

}  // namespace ubersim::dds
