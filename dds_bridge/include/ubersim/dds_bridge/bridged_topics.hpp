#pragma once
// The topics the bridge can carry: each LCM channel maps one for one onto a
// DDS topic. The order is the one a config's routes, the start log and the
// stop summary list them in.
#include <array>
#include <string_view>
#include <tuple>

#include "ubersim/topics.hpp"

namespace ubersim::dds {

inline constexpr auto kBridgedTopics = std::make_tuple(
    topics::kVision, topics::kVisionGeometry, topics::kRadio.yellow, topics::kRadio.blue,
    topics::kRadioFeedback.yellow, topics::kRadioFeedback.blue, topics::kSimCommands,
    topics::kSimState, topics::kSimControl, topics::kSimControlAck, topics::kSimGeometry);

// Calls visit(topic) for every bridged topic, in order (each a Topic<Msg> of its own type).
template <class Visit>
void for_each_bridged_topic(Visit&& visit) {
  std::apply([&](const auto&... topic) { (visit(topic), ...); }, kBridgedTopics);
}

// The bridged topics' base names (the config's keys), in the same order.
inline constexpr auto kBridgedChannels = std::apply(
    [](const auto&... topic) {
      return std::array<std::string_view, sizeof...(topic)>{topic.name...};
    },
    kBridgedTopics);

}  // namespace ubersim::dds
