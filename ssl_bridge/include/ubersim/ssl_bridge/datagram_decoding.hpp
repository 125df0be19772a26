#pragma once
// The first thing every datagram on the simulation and robot control ports
// goes through: a protobuf decode that costs no more than the datagram's size
// allows. Nesting is limited, every repeated field is capped, and fields the
// protocol does not have are counted and dropped before any translation sees
// the message. The bridge and the fuzz targets (fuzz/) call exactly this.
#include <google/protobuf/message.h>

#include <cstddef>
#include <cstdint>

#include "ubersim/ssl_bridge/errors.hpp"

namespace ubersim::ssl {

// Largest UDP payload over IPv4; a larger "datagram" cannot come from a socket.
inline constexpr std::size_t kMaxDatagramBytes = 65507;
// Nesting protobuf's parser takes (its default for every parse; ours nest at
// most 6 deep: SimulatorCommand > config > geometry > field > field_lines > p1).
// An unknown group field nested deeper is refused, not recursed into.
inline constexpr int kDecodeRecursionLimit = 100;
// Elements of any one repeated field: a team has at most 16 robot ids, a field
// a few dozen lines, a vision system a few cameras. More is refused as a whole,
// so a 64 KB datagram of empty elements cannot become 30,000 radio commands.
inline constexpr int kMaxRepeatedElements = 64;

struct DecodedDatagram {
  bool ok = false;                 // decoded and within the limits: translate it
  std::size_t unknown_fields = 0;  // fields the protocol lacks, dropped (message still ok)
};

// Decodes `size` bytes into `message` (cleared first). On failure an error with
// code UBERSIM_MALFORMED or UBERSIM_TOO_LARGE is added; unknown fields add one
// UBERSIM_UNKNOWN_FIELDS error and are removed from the message. With
// `missing_required_ok` a message that lacks required fields is taken as far
// as it goes (grSim's port: grSim reads every field with has_...()).
DecodedDatagram decode_datagram(const std::uint8_t* data, std::size_t size,
                                google::protobuf::Message& message, Errors& errors,
                                bool missing_required_ok = false);

}  // namespace ubersim::ssl
