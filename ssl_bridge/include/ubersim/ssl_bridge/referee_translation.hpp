#pragma once
// REFEREE (referee_t, from ubersim_referee auto) -> the SSL game controller's
// Referee message (ssl_gc_referee_message.proto), as the real game controller
// sends it on 224.5.23.1:10003. Stages, commands and event types already use
// the SSL numbers; units become the protocol's (µs, mm for the designated
// position, m in game events). Timestamps are µs of simulation time, the one
// time base of every SSL packet the bridge sends (docs/ssl_bridge.md, "Time
// stamps"): the packet's is the sim time of the state the referee judged, a
// command's the sim time it was issued, an event's the sim time it happened.
#include <ssl_gc_referee_message.pb.h>

#include <cstdint>
#include <string>
#include <ubersim/referee_t.hpp>

namespace ubersim::ssl {

class RefereeTranslator {
 public:
  explicit RefereeTranslator(std::string source_identifier)
      : source_identifier_(std::move(source_identifier)) {}

  Referee translate(const referee_t& referee) const;

 private:
  std::string source_identifier_;
};

// One game event, its payload in the oneof field of its type.
GameEvent to_ssl_game_event(const referee_event_t& event);

// Seconds of sim time as the protocol's µs; what is no time (not finite, negative, beyond 1e9 s)
// is 0.
std::uint64_t sim_time_us(double seconds);

}  // namespace ubersim::ssl
