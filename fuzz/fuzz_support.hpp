#pragma once
// What the fuzz targets (and their seed writer) share.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "ubersim/spdlog.hpp"

namespace ubersim::fuzz {

// The code under test logs bad input (throttled); at a million inputs a
// second that is only noise in the fuzzer's output.
inline void quiet_logging() {
  spdlog::set_level(spdlog::level::off);
}

// An LCM message's bytes as they go on the bus. It must encode to the size it
// announces (its counts match its arrays; with ASan a count larger than its
// array is a read out of bounds); anything else aborts: in a target, a
// finding, for a message the code under test built or one it decoded; in the
// seed writer, a broken seed.
template <class Msg>
std::string encode_or_abort(const Msg& message) {
  const int size = message.getEncodedSize();
  std::string bytes(static_cast<std::size_t>(size), '\0');
  if (message.encode(bytes.data(), 0, size) != size) std::abort();
  return bytes;
}

// An input of a target that takes one datagram on one of several channels:
// the first byte picks the channel (modulo the selector's Count), the rest is the datagram.
template <class Selector>
struct ChannelInput {
  Selector channel;
  const std::uint8_t* bytes;
  std::size_t length;
};

// Needs size >= 1.
template <class Selector>
ChannelInput<Selector> channel_input(const std::uint8_t* data, std::size_t size) {
  const int count = static_cast<int>(Selector::Count);
  return {static_cast<Selector>(data[0] % count), data + 1, size - 1};
}

}  // namespace ubersim::fuzz
