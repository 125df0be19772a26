#pragma once
// The LCM door of the team group (docs/timeshim.md, "Team programs that speak
// LCM"): a team program the bridge starts under the time shim that speaks our
// LCM contract (VISION, VISION_GEOMETRY, REFEREE, RADIO_FEEDBACK_<TEAM> in,
// RADIO_<TEAM> out) gets a private LCM bus of its own (its LCM_DEFAULT_URL, a
// udpm URL on a port of its own, ttl=0). The door relays the main bus onto it,
// gated by sim time as the bridge gates its SSL outputs, and at each
// quiescence drains the team's RADIO_<TEAM> from it: each packet goes to the
// main bus stamped with the sim time at which the team sent it.
//
// Why a private bus and not the main one: on the main bus the team would hear
// every frame the moment the vision emulator sends it (wall time, ahead of the
// group's sim time), and its commands would reach the radio unstamped; on its
// own bus it hears only what the bridge hands it, when the bridge hands it.
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <ubersim/radio_feedback_t.hpp>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/referee_t.hpp>
#include <ubersim/vision_frame_t.hpp>
#include <ubersim/vision_geometry_t.hpp>
#include <utility>
#include <vector>

#include "ubersim/channels.hpp"
#include "ubersim/message_bus.hpp"
#include "ubersim/ssl_bridge/team_group.hpp"

namespace ubersim::ssl {

struct LcmDoorOptions {
  std::vector<Team> teams;  // the teams whose program speaks LCM (--team-protocol COLOUR lcm)
  std::string url;          // the private bus (--team-lcm-url; default: main bus' port + 1)
};

// The private bus for a main bus URL: same group, the next port, ttl=0;
// nullopt when the main URL is not udpm://ADDRESS:PORT.
std::optional<std::string> private_lcm_url(const std::string& main_url);
// COMMAND run with LCM_DEFAULT_URL = url (for /bin/sh -c).
std::string with_lcm_url(const std::string& command, const std::string& url);
// The --team-protocol COLOUR PROTOCOL pairs (ssl | lcm | grsim) set each
// team command's protocol; each LCM team also goes into `door` and its
// command gets the private bus (door.url, or the one of main_url). Returns an
// error text for the command line, or "".
std::string apply_team_protocols(const std::vector<std::pair<std::string, std::string>>& protocols,
                                 const std::string& main_url, TeamGroupOptions& teams,
                                 LcmDoorOptions& door);
// The colours whose team command speaks grSim's protocol (both colours for "both").
std::vector<Team> grsim_teams(const TeamGroupOptions& teams);

class LcmTeamDoor {
 public:
  // Publishes a team's packet on the main bus (the bridge numbers it, as its
  // promises, so that a team's RADIO_<TEAM> has one sequence).
  using PublishRadio = std::function<void(Team, radio_packet_t&)>;

  // Subscribes on `main` to what the teams hear; opens the private bus
  // (throws std::runtime_error when LCM cannot).
  LcmTeamDoor(MessageBus& main, const ChannelNames& channels, LcmDoorOptions options,
              PublishRadio publish_radio);
  LcmTeamDoor(const LcmTeamDoor&) = delete;
  LcmTeamDoor& operator=(const LcmTeamDoor&) = delete;

  const std::string& url() const { return options_.url; }
  // A vision frame of the step being delivered (the bridge's on_vision).
  void hold(const vision_frame_t& frame);
  // The frames held and the geometry of t (s of sim time), and the referee
  // messages and feedback up to `settled` (all of them are here up to then:
  // latest_before, timed_inputs.hpp), onto the private bus.
  void deliver(double t, double settled);
  // At a quiescence at now_ns: every RADIO_<TEAM> the teams sent is here;
  // each goes to the main bus with t_sent = now. Returns how many.
  int drain(std::int64_t now_ns);
  // The team programs ended: nothing is held any more.
  void stop_holding();
  std::string summary() const;

 private:
  void deliver_geometry(double t);

  MessageBus& main_;
  ChannelNames channels_;
  LcmDoorOptions options_;
  PublishRadio publish_radio_;
  MessageBus private_;
  bool holding_ = true;
  std::vector<vision_frame_t> vision_;
  std::string geometry_;       // the latest VISION_GEOMETRY, encoded
  std::string geometry_sent_;  // the one the teams got last
  double geometry_next_ = 0;   // s, sim time it is sent again
  std::vector<referee_t> referee_;
  std::vector<radio_feedback_t> feedback_;
  std::int64_t draining_at_ns_ = 0;
  std::map<std::string, std::uint64_t> counters_;
};

}  // namespace ubersim::ssl
