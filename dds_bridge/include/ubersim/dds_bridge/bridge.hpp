#pragma once
// The bridge core: for every channel of a BridgeConfig, an LCM subscription
// that writes to a DDS topic and/or a DDS reader whose samples are checked
// (sample_checks.hpp) and published on LCM.
//
// Single-threaded: LCM handlers run in MessageBus::handle_pending(); DDS
// readers only signal wake_fd() (from Cyclone's listener thread) and their
// samples are taken and forwarded in take_dds(), called by the same loop.
//
// No loops: a DDS sample the bridge wrote never reaches its own readers
// (ignore-local, qos.hpp), and an LCM message the bridge published is not sent
// back to DDS when the bridge hears it (echo_filter.hpp).
#include <dds/dds.h>

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "ubersim/channels.hpp"
#include "ubersim/dds_bridge/bridge_config.hpp"
#include "ubersim/message_bus.hpp"
#include "ubersim/radio/radio_profile.hpp"

namespace ubersim::dds {

// What crossed in one direction of one channel.
struct RouteStats {
  std::uint64_t received = 0;         // messages / valid samples taken in
  std::uint64_t forwarded = 0;        // published on the other side
  std::uint64_t dropped = 0;          // bad samples dropped whole
  std::uint64_t entries_removed = 0;  // bad robot entries removed from samples that went on
  std::uint64_t echoes = 0;           // the bridge's own LCM messages heard back, not re-sent
  std::uint64_t write_errors = 0;     // DDS writes that failed
  std::map<std::string, std::uint64_t> problems;  // findings by kind ("NaN/Inf", ...)
};

class Bridge {
 public:
  // Creates every topic, reader, writer and subscription. Throws DdsError.
  Bridge(const BridgeConfig& config, const ChannelNames& channels,
         const radio::CommandLimits& radio_limits, dds_entity_t participant, MessageBus& bus);
  ~Bridge();
  Bridge(const Bridge&) = delete;
  Bridge& operator=(const Bridge&) = delete;

  // Readable when a DDS reader has data; take_dds() clears it.
  int wake_fd() const { return wake_fd_; }
  // Takes every waiting DDS sample and forwards what passes the checks.
  // Returns how many samples were taken.
  int take_dds();

  // Asks physics on LCM (SIM_CONTROL, REQUEST_GEOMETRY) to publish the field
  // now, so that the geometry topic holds it for late DDS joiners at once.
  void request_sim_geometry();

  // Per bridged channel (a topic's base name) and direction.
  const RouteStats& stats(std::string_view channel, Direction direction) const;
  // One line per bridged channel and direction, for the log.
  std::vector<std::string> describe_routes() const;
  std::vector<std::string> summary() const;

  struct Link;  // one bridged channel (bridge.cpp)

 private:
  template <class Lcm, class Admit>
  void add(const Topic<Lcm>& lcm_topic, const Route& route, const ChannelNames& channels,
           Admit admit);
  template <class Lcm>
  void publish_lcm(Link& link, const Lcm& message);

  dds_entity_t participant_;
  MessageBus& bus_;
  int wake_fd_ = -1;
  std::vector<std::unique_ptr<Link>> links_;
  std::string sim_control_channel_;
};

}  // namespace ubersim::dds
