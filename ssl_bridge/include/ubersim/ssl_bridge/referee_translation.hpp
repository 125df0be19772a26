#pragma once
// REFEREE (referee_t, from ubersim_referee auto) -> the SSL game controller's
// Referee message (ssl_gc_referee_message.proto), as the real game controller
// sends it on 224.5.23.1:10003. Stages, commands and event types already use
// the SSL numbers; units become the protocol's (µs, mm for the designated
// position, m in game events). Timestamps are UNIX µs of wall time, as SSL
// software expects: the packet's is "now", a command's is when the bridge
// first saw it.
#include <ssl_gc_referee_message.pb.h>

#include <cstdint>
#include <string>
#include <ubersim/referee_t.hpp>

namespace ubersim::ssl {

class RefereeTranslator {
 public:
  explicit RefereeTranslator(std::string source_identifier)
      : source_identifier_(std::move(source_identifier)) {}

  // now_us: UNIX time in µs.
  Referee translate(const referee_t& referee, std::uint64_t now_us);

 private:
  std::string source_identifier_;
  std::int64_t last_counter_ = -1;
  std::uint64_t command_timestamp_us_ = 0;
};

// One game event, its payload in the oneof field of its type.
GameEvent to_ssl_game_event(const referee_event_t& event, std::uint64_t now_us);

}  // namespace ubersim::ssl
