#pragma once
// Keeps a message the bridge published on LCM from crossing back to DDS.
//
// LCM delivers a process's own publications back to its subscriptions and
// carries no sender id, so the bridge remembers the encoded bytes of what it
// published on a channel for a short window and drops any message on that
// channel whose bytes are identical. A byte-identical message from someone else
// within the window is dropped too: it is a duplicate of what DDS already has.
// (The DDS side needs no such filter: the bridge's readers ignore their own
// participant's writers, see qos.hpp.)
#include <chrono>
#include <cstdint>
#include <deque>
#include <vector>

namespace ubersim::dds {

class EchoFilter {
 public:
  using Clock = std::chrono::steady_clock;
  using Bytes = std::vector<std::uint8_t>;

  explicit EchoFilter(Clock::duration window = std::chrono::seconds(2), std::size_t capacity = 256)
      : window_(window), capacity_(capacity) {}

  void remember(Bytes bytes, Clock::time_point now = Clock::now());
  // True when `bytes` equal a message remembered within the window.
  bool is_echo(const Bytes& bytes, Clock::time_point now = Clock::now());
  bool empty() const { return sent_.empty(); }

 private:
  struct Sent {
    Clock::time_point time;
    std::uint64_t hash;
    Bytes bytes;
  };
  void forget_older_than(Clock::time_point now);

  Clock::duration window_;
  std::size_t capacity_;
  std::deque<Sent> sent_;
};

// The LCM encoding of a message (what goes on the wire after the header).
template <class Msg>
EchoFilter::Bytes lcm_bytes(const Msg& message) {
  EchoFilter::Bytes bytes(static_cast<std::size_t>(message.getEncodedSize()));
  message.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

}  // namespace ubersim::dds
