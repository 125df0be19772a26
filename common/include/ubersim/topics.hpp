#pragma once
// Typed topics: one descriptor per LCM channel, holding its name and, in its
// type, the message it carries. Subscribing or publishing through a Topic
// picks the message type from it, so a wrong type does not compile:
//
//   subscribe(bus, channels, topics::kSimState, [](const sim_state_t& s) { ... });
//   publish(bus, channels, topics::kReferee, referee);  // referee_t, or no build
//
// The channel table (README.md, "Processes and channels") is printed from
// topic_table() by `ubersim_channels --markdown`; test_channel_table fails
// when the README and this file disagree.
#include <array>
#include <functional>
#include <string>
#include <string_view>
#include <ubersim/emulator_realism_t.hpp>
#include <ubersim/field_geometry_t.hpp>
#include <ubersim/radio_feedback_t.hpp>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/referee_t.hpp>
#include <ubersim/sim_commands_t.hpp>
#include <ubersim/sim_control_ack_t.hpp>
#include <ubersim/sim_control_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <ubersim/sync_client_t.hpp>
#include <ubersim/sync_horizon_t.hpp>
#include <ubersim/sync_status_t.hpp>
#include <ubersim/truth_demand_t.hpp>
#include <ubersim/vision_cameras_t.hpp>
#include <ubersim/vision_frame_t.hpp>
#include <ubersim/vision_geometry_t.hpp>
#include <ubersim/vision_schedule_t.hpp>
#include <vector>

#include "ubersim/channels.hpp"
#include "ubersim/message_bus.hpp"

namespace ubersim {

// A channel and the one message type it carries. `name` is the base name, as
// --channel-prefix and --channel NAME=OTHER see it.
template <class Msg>
struct Topic {
  using Message = Msg;
  std::string_view name;
};

// A pair of channels, one per team, of one message type (RADIO_YELLOW / RADIO_BLUE).
template <class Msg>
struct TeamTopic {
  Topic<Msg> yellow;
  Topic<Msg> blue;
  constexpr Topic<Msg> of(Team team) const { return team == Team::Yellow ? yellow : blue; }
};

namespace topics {
inline constexpr Topic<vision_frame_t> kVision{"VISION"};
inline constexpr Topic<vision_geometry_t> kVisionGeometry{"VISION_GEOMETRY"};
inline constexpr TeamTopic<radio_packet_t> kRadio{{"RADIO_YELLOW"}, {"RADIO_BLUE"}};
inline constexpr TeamTopic<radio_feedback_t> kRadioFeedback{{"RADIO_FEEDBACK_YELLOW"},
                                                            {"RADIO_FEEDBACK_BLUE"}};
inline constexpr Topic<sim_commands_t> kSimCommands{"SIM_COMMANDS"};
inline constexpr Topic<sim_state_t> kSimState{"SIM_STATE"};
inline constexpr Topic<sim_control_t> kSimControl{"SIM_CONTROL"};
inline constexpr Topic<sim_control_ack_t> kSimControlAck{"SIM_CONTROL_ACK"};
inline constexpr Topic<field_geometry_t> kSimGeometry{"SIM_GEOMETRY"};
inline constexpr Topic<vision_schedule_t> kVisionSchedule{"SIM_VISION_SCHEDULE"};
inline constexpr Topic<sync_client_t> kSyncClient{"SYNC_CLIENT"};
inline constexpr Topic<sync_horizon_t> kSyncHorizon{"SIM_SYNC_HORIZON"};
inline constexpr Topic<sync_status_t> kSyncStatus{"SIM_SYNC_STATUS"};
inline constexpr Topic<referee_t> kReferee{"REFEREE"};
inline constexpr Topic<emulator_realism_t> kEmulatorRealism{"EMULATOR_REALISM"};
inline constexpr Topic<vision_cameras_t> kVisionCameras{"VISION_CAMERAS"};
inline constexpr Topic<truth_demand_t> kTruthDemand{"SIM_TRUTH_DEMAND"};

// Every topic's base name: what --channel NAME=OTHER may override.
inline constexpr std::array<std::string_view, 19> kAllNames{kVision.name,
                                                            kVisionGeometry.name,
                                                            kRadio.yellow.name,
                                                            kRadio.blue.name,
                                                            kRadioFeedback.yellow.name,
                                                            kRadioFeedback.blue.name,
                                                            kSimCommands.name,
                                                            kSimState.name,
                                                            kSimControl.name,
                                                            kSimControlAck.name,
                                                            kSimGeometry.name,
                                                            kVisionSchedule.name,
                                                            kSyncClient.name,
                                                            kSyncHorizon.name,
                                                            kSyncStatus.name,
                                                            kReferee.name,
                                                            kEmulatorRealism.name,
                                                            kVisionCameras.name,
                                                            kTruthDemand.name};
}  // namespace topics

// The channel name a topic has in this process (prefix and overrides applied).
template <class Msg>
std::string channel_name(const ChannelNames& channels, const Topic<Msg>& topic) {
  return channels.resolve(topic.name);
}

template <class Msg>
void subscribe(MessageBus& bus, const ChannelNames& channels, const Topic<Msg>& topic,
               std::function<void(const typename Topic<Msg>::Message&)> handler,
               int queue_capacity = 1000) {
  bus.subscribe<Msg>(channel_name(channels, topic), std::move(handler), queue_capacity);
}

// Like subscribe, but a message on the topic never wakes the loop: it is read
// when the loop wakes for anything else (MessageBus::subscribe_unhurried).
template <class Msg>
void subscribe_unhurried(MessageBus& bus, const ChannelNames& channels, const Topic<Msg>& topic,
                         std::function<void(const typename Topic<Msg>::Message&)> handler) {
  bus.subscribe_unhurried<Msg>(channel_name(channels, topic), std::move(handler));
}

template <class Msg>
void publish(MessageBus& bus, const ChannelNames& channels, const Topic<Msg>& topic,
             const typename Topic<Msg>::Message& message) {
  bus.publish(channel_name(channels, topic), message);
}

// A topic's publisher with the channel name resolved once, for a hot path (a
// message or more per wakeup): publish() builds the name on every call.
template <class Msg>
class Publisher {
 public:
  Publisher(MessageBus& bus, const ChannelNames& channels, const Topic<Msg>& topic)
      : bus_(&bus), channel_(channel_name(channels, topic)) {}
  void operator()(const typename Topic<Msg>::Message& message) const {
    bus_->publish(channel_, message);
  }
  const std::string& channel() const { return channel_; }

 private:
  MessageBus* bus_;
  std::string channel_;
};

// A program of this tree that publishes or reads channels. Each row of the
// channel table lists them, and test_channel_wiring checks the lists against
// the programs' code (tests/lint/channel_wiring.py): a use of a topic in the
// code that a row does not list, or a row's entry the code does not have, fails.
enum class Program {
  Physics,
  VisionEmulator,
  RadioEmulator,
  Referee,
  GcLink,
  SslBridge,
  Viewer,
  DemoTeam,
  ReportRig,
};
// A program in a row, with a note for the reader ("in sync mode").
struct Role {
  Program program;
  std::string_view note = {};
};

// One row of the channel table: who publishes and reads a topic, and how often.
struct TopicRow {
  std::string base_name;  // the first channel's base name: RADIO_YELLOW for the pair
  std::string channels;   // "`RADIO_YELLOW`, `RADIO_BLUE`"
  std::string type;       // the LCM type's name
  std::vector<Role> publishers;
  std::vector<Role> readers;
  std::string rate;
};
std::vector<TopicRow> topic_table();
// The program's id in `ubersim_channels --wiring` (channel_wiring.py's names).
std::string_view program_id(Program program);
// One line per program and channel ("VISION reads viewer"), for test_channel_wiring.
std::string topic_table_wiring();
// The table as Markdown, the form README.md holds.
std::string topic_table_markdown();

}  // namespace ubersim
