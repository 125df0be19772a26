#pragma once
// The one place that decides every LCM channel name. A prefix ("SIM2_") lets
// several simulations share one network; per-channel overrides ("VISION=CAM")
// let a process listen where an existing stack already publishes.
#include <array>
#include <map>
#include <string>

namespace ubersim {

enum class Team : int { Yellow = 0, Blue = 1 };
inline constexpr std::array<Team, 2> kTeams{Team::Yellow, Team::Blue};
const char* team_name(Team team);                      // "yellow" / "blue"
std::string robot_name(Team team, int id);             // "yellow 3", for messages
bool parse_team(const std::string& text, Team& team);  // accepts yellow/blue/y/b/0/1

enum class Channel {
  Vision,               // vision_frame_t, vision server -> control
  VisionGeometry,       // vision_geometry_t, vision server -> control
  RadioYellow,          // radio_packet_t, yellow control -> radio server
  RadioBlue,            // radio_packet_t, blue control -> radio server
  RadioFeedbackYellow,  // radio_feedback_t, radio server -> yellow control
  RadioFeedbackBlue,    // radio_feedback_t, radio server -> blue control
  SimCommands,          // sim_commands_t, radio emulator -> physics
  SimState,             // sim_state_t, physics -> emulators and tools
  SimControl,           // sim_control_t, referee and tools -> physics
  SimControlAck,        // sim_control_ack_t, physics -> referee and tools
  SimGeometry,          // field_geometry_t, physics -> vision emulator and tools
};
inline constexpr std::array<Channel, 11> kAllChannels{Channel::Vision,
                                                      Channel::VisionGeometry,
                                                      Channel::RadioYellow,
                                                      Channel::RadioBlue,
                                                      Channel::RadioFeedbackYellow,
                                                      Channel::RadioFeedbackBlue,
                                                      Channel::SimCommands,
                                                      Channel::SimState,
                                                      Channel::SimControl,
                                                      Channel::SimControlAck,
                                                      Channel::SimGeometry};

inline constexpr const char* kEmulatorRealismChannel = "EMULATOR_REALISM";
// A new camera set for the vision emulator (vision_cameras_t; SSL bridge, tools).
inline constexpr const char* kVisionCamerasChannel = "VISION_CAMERAS";
// Sync mode's coordination (docs/sync.md), low rate, on the main bus.
inline constexpr const char* kSyncClientChannel = "SYNC_CLIENT";              // sync_client_t
inline constexpr const char* kSyncHorizonChannel = "SIM_SYNC_HORIZON";        // sync_horizon_t
inline constexpr const char* kVisionScheduleChannel = "SIM_VISION_SCHEDULE";  // vision_schedule_t
// Dropped and rejoined sync clients (radio emulator -> referee, tools).
inline constexpr const char* kSyncStatusChannel = "SIM_SYNC_STATUS";  // sync_status_t
// The automatic referee's game state (referee_t, docs/autoref.md).
inline constexpr const char* kRefereeChannel = "REFEREE";
// Which ground-truth states each consumer needs (physics --truth-on-demand).
inline constexpr const char* kTruthDemandChannel = "SIM_TRUTH_DEMAND";  // truth_demand_t
// Channels outside the Channel list (which the DDS bridge maps one for one
// onto topics): these have no DDS topic.
inline constexpr std::array<const char*, 8> kExtraChannels{
    kEmulatorRealismChannel, kSyncClientChannel,  kSyncHorizonChannel,   kVisionScheduleChannel,
    kRefereeChannel,         kTruthDemandChannel, kVisionCamerasChannel, kSyncStatusChannel};

// The name a channel has with no prefix and no override, e.g. "RADIO_YELLOW".
const char* base_channel_name(Channel channel);

class ChannelNames {
 public:
  ChannelNames() = default;
  // Throws std::invalid_argument for an override of a channel that does not exist.
  ChannelNames(std::string prefix, std::map<std::string, std::string> overrides);

  std::string operator()(Channel channel) const;
  std::string radio(Team team) const;
  std::string radio_feedback(Team team) const;
  // EMULATOR_REALISM (emulator_realism_t, SSL bridge and tools -> vision and
  // radio emulators). Outside the Channel list, which the DDS bridge maps one
  // for one onto topics: this one has no DDS topic.
  std::string emulator_realism() const { return extra(kEmulatorRealismChannel); }
  // VISION_CAMERAS (vision_cameras_t, SSL bridge and tools -> vision emulator).
  std::string vision_cameras() const { return extra(kVisionCamerasChannel); }
  // One of kExtraChannels, with the prefix or its override.
  std::string extra(const char* base) const;
  // REFEREE (referee_t, automatic referee -> control software, SSL bridge).
  std::string referee() const { return extra(kRefereeChannel); }

  // Parses "BASE_NAME=CHANNEL" as given on a command line.
  static std::pair<std::string, std::string> parse_override(const std::string& text);

 private:
  std::string prefix_;
  std::map<std::string, std::string> overrides_;
};

}  // namespace ubersim
