#pragma once
// grSim's own protocol on the bridge (docs/ssl_bridge.md, "grSim's protocol"):
// grSim_Packet datagrams on UDP 20011 -> the newest command per robot ->
// radio_packet_t on RADIO_<TEAM> (through the radio emulator, like every
// team's commands), replacements -> SIM_CONTROL; Robots_Status from
// RADIO_FEEDBACK_<TEAM> back to the sender's address, port 30011 (blue) /
// 30012 (yellow). Built to take a flood: a wakeup reads a bounded number of
// datagrams into one buffer, a team gets at most one radio packet per
// kGrsimPublishInterval, and nothing queues but the newest command per robot.
#include <netinet/in.h>

#include <array>
#include <chrono>
#include <cstdint>
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
  GrsimPort(MessageBus& bus, const ChannelNames& channels, GrsimOptions options);
  // Watches the port on the bus.
  void start();
  // After every wakeup: sends what waited for its interval, repeats, stops.
  void tick(Clock::time_point now);
  // When tick() has something to do next (nullopt: nothing until a datagram).
  std::optional<Clock::time_point> next_wake() const;
  void log_summary() const;

 private:
  void on_readable();
  void handle_datagram(const std::uint8_t* data, std::size_t size, const sockaddr_in& from,
                       Clock::time_point now);
  void handle_commands(const grSim_Commands& commands, Clock::time_point now);
  void handle_replacement(const grSim_Replacement& replacement);
  void send_status(const sockaddr_in& sender);
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
  ThrottledLog bad_input_;
  std::map<std::string, std::uint64_t> counters_;
};

}  // namespace ubersim::ssl
