#pragma once
// grSim's own protocol on the bridge (docs/ssl_bridge.md, "grSim's protocol"):
// grSim_Packet datagrams on UDP 20011 -> the newest command per robot ->
// radio_packet_t on RADIO_<TEAM> (through the radio emulator, like every
// team's commands), replacements -> SIM_CONTROL; Robots_Status from
// RADIO_FEEDBACK_<TEAM> back to the sender's address, port 30011 (blue) /
// 30012 (yellow). Built to take a flood: a wakeup reads a bounded number of
// datagrams into one buffer, a team gets at most one radio packet per
// kGrsimPublishInterval, and nothing queues but the newest command per robot.
//
// Timed teams (gate(), docs/timeshim.md, "Team programs that speak grSim's
// protocol"): for team programs the SSL bridge runs under the time shim, the
// port is read at the team group's quiescences (drain_timed) instead: each
// timed team's commands go out once per quiescence, stamped with the group's
// sim time, and the book's clock (kick window, repeats, the silent team's
// stop) is sim time. Command packets for any other colour are counted and
// dropped while the group runs: that colour's RADIO_<TEAM> belongs to a sync
// client, where unstamped packets would be out of order.
#include <netinet/in.h>

#include <array>
#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <ubersim/radio_feedback_t.hpp>
#include <ubersim/sim_control_ack_t.hpp>
#include <vector>

#include "ubersim/channels.hpp"
#include "ubersim/logging.hpp"
#include "ubersim/message_bus.hpp"
#include "ubersim/ssl_bridge/grsim_command_book.hpp"
#include "ubersim/ssl_bridge/grsim_status.hpp"
#include "ubersim/ssl_bridge/grsim_translation.hpp"
#include "ubersim/ssl_bridge/held_for_next_frame.hpp"
#include "ubersim/ssl_bridge/latest_state.hpp"
#include "ubersim/ssl_bridge/sim_control_translation.hpp"
#include "ubersim/ssl_bridge/udp_socket.hpp"

namespace ubersim::ssl {

// A team's radio packets from grSim commands are at least this far apart.
inline constexpr std::chrono::microseconds kGrsimPublishInterval{2000};
// A held team's commands are said again this often while it is silent, well
// within the radio profiles' command timeouts (0.1 s and more).
inline constexpr std::chrono::milliseconds kGrsimRepeatInterval{40};
// Datagrams one wakeup reads from the grSim port.
inline constexpr int kGrsimDatagramsPerWakeup = 1024;

struct GrsimOptions {
  int port = 20011;  // 0: grSim's protocol off
  std::string listen_address = "127.0.0.1";
  int blue_status_port = 30011;
  int yellow_status_port = 30012;
  double command_hold = 1.0;  // s of wall time a silent team keeps its commands; 0: for ever
  GrsimTranslationSettings translation;
  SimControlSettings sim_control;
};

class GrsimPort {
 public:
  using Clock = std::chrono::steady_clock;
  // Publishes a timed team's radio packet (the bridge numbers it with the
  // team's promises, and holds it until the team registered).
  using PublishTimed = std::function<void(Team, radio_packet_t)>;
  // Which team program sent from this address (held_for_next_frame.hpp).
  using ProgramOf = std::function<std::size_t(const sockaddr_in&)>;

  GrsimPort(MessageBus& bus, const ChannelNames& channels, GrsimOptions options);
  // Before start(): these colours are grSim-protocol teams under the time shim.
  void gate(std::vector<Team> timed_teams, PublishTimed publish, ProgramOf program_of);
  // Watches the port on the bus.
  void start();
  // At a quiescence of the team group at now_ns (sim time): every datagram the
  // group sent is waiting; each timed team's commands go out stamped now_ns.
  // The robot status takes the feedback sent up to now_ns and up to `settled`
  // (s: all of it is here up to then; SslBridge::add_timed_door).
  // True when a robot status went back to the group (it must run again).
  bool drain_timed(std::int64_t now_ns, double settled);
  // A frame goes to the group: the replacements its grSim teams sent since
  // the last go to physics, which waits at that frame's state, so they apply
  // there on every run (SslBridge::apply_timed_controls, for the simulation
  // protocol).
  void release_replacements();
  // The team programs ended: back to the real-time rules.
  void stop_gating();
  // After every wakeup: sends what waited for its interval, repeats, stops.
  void tick(Clock::time_point now);
  // When tick() has something to do next (nullopt: nothing until a datagram).
  std::optional<Clock::time_point> next_wake() const;
  void log_summary() const;

 private:
  // Where a datagram was read: in the bus loop, or at a team group's quiescence.
  enum class Arrival { RealTime, AtQuiescence };

  void on_readable();
  // Reads and handles one datagram; false when none waits.
  bool receive_one(Clock::time_point now, Arrival arrival);
  void handle_datagram(const std::uint8_t* data, std::size_t size, const sockaddr_in& from,
                       Clock::time_point now, Arrival arrival);
  void handle_commands(const grSim_Commands& commands, Clock::time_point now, Arrival arrival);
  // Gated: a packet for `team` read this way is dropped (counted, logged).
  bool refused_while_gated(Team team, Arrival arrival);
  bool timed(Team team) const;
  void on_feedback(Team team, const radio_feedback_t& feedback);
  void apply_feedback(Team team, const radio_feedback_t& feedback);
  void handle_replacement(const grSim_Replacement& replacement);
  // True when it sent a status packet.
  bool send_status(const sockaddr_in& sender);
  void flush(Clock::time_point now);
  void publish(Team team, radio_packet_t packet);
  void on_ack(const sim_control_ack_t& ack);
  void count_errors(const Errors& errors, const std::string& what);

  MessageBus& bus_;
  ChannelNames channels_;
  GrsimOptions options_;
  UdpSocket socket_;
  std::vector<std::uint8_t> buffer_;  // one datagram at a time, the largest UDP payload
  std::uint32_t kernel_drops_ = 0;    // SO_RXQ_OVFL: datagrams the full socket buffer lost
  GrsimCommandBook book_;
  GrsimStatus status_;
  LatestState state_;
  std::array<Clock::time_point, 2> last_publish_{};
  std::array<std::int64_t, 2> sequence_{};
  std::int64_t next_request_id_ = 1;
  // Timed teams (gate()): their colours, where their packets go, the feedback
  // held until the group's sim time reaches it, and whether the group runs.
  std::vector<Team> timed_teams_;
  PublishTimed publish_timed_;
  ProgramOf program_of_;
  std::vector<std::pair<Team, radio_feedback_t>> held_feedback_;
  bool gated_ = false;
  bool statuses_sent_ = false;                             // during a drain
  HeldForNextFrame<grSim_Replacement> held_replacements_;  // release_replacements
  ThrottledLog bad_input_;
  std::map<std::string, std::uint64_t> counters_;
};

}  // namespace ubersim::ssl
