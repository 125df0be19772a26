#pragma once
// LCM's UDP multicast wire format, received in the caller's own thread.
//
// LCM 1.3.1 receives on a thread of its own that wakes for every datagram on
// the group and hands each wanted one to the process's loop through a pipe:
// two thread wakeups per message, each 20-30 us in a VM, whatever the message
// is. This receiver is the same socket LCM would open (same group, port and
// options), read by the loop itself with recvmmsg, with the kernel-side
// channel filter of lcm_channel_filter.hpp: one wakeup per wakeup's worth of
// wanted messages, none for the others. Publishing stays with LCM.
//
// What it accepts is what LCM 1.3.1 accepts of a short message ('LC02':
// magic, sequence number, channel name of at most 63 bytes and its NUL,
// payload). A fragmented message (over 64 KB, 'LC03') is counted and dropped:
// no message of ubersim comes near that size, and reassembling one would
// allocate what its first fragment announces before the rest is there.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace ubersim {

struct LcmUdpmAddress {
  std::string group;  // dotted IPv4
  int port = 0;
  int receive_buffer_bytes = 0;  // recv_buf_size=, 0 = the kernel's default
};

// The address of a udpm:// URL, or nothing for another provider (memq://,
// file://). "" means $LCM_DEFAULT_URL, then LCM's default, as lcm::LCM reads it.
std::optional<LcmUdpmAddress> parse_lcm_udpm_url(const std::string& url);

class LcmUdpmReceiver {
 public:
  // channel, payload, payload size, receive time (us since the epoch)
  using Deliver = std::function<void(const char*, const void*, std::size_t, std::int64_t)>;

  // Throws std::runtime_error when the socket cannot be opened or joined.
  explicit LcmUdpmReceiver(const LcmUdpmAddress& address);
  ~LcmUdpmReceiver();
  LcmUdpmReceiver(const LcmUdpmReceiver&) = delete;
  LcmUdpmReceiver& operator=(const LcmUdpmReceiver&) = delete;

  int fd() const { return fd_; }

  // Only these channels reach the process (checked in the kernel).
  void want_channels(const std::set<std::string>& channels);

  // Why a datagram that reached the process was dropped ("fragment": a
  // message over 64 KB; "not LCM": no LCM short message).
  using Drop = std::function<void(const char*, std::size_t)>;

  // Reads what waits, at most `budget` datagrams, and delivers each LCM short
  // message; returns how many datagrams it read. Never blocks.
  // before_delivering, when given, runs after each batch is read and before
  // any of it is delivered (MessageBus reads its unhurried socket there, so
  // that what was sent before a message here is delivered before it).
  int receive(int budget, const Deliver& deliver, const Drop& drop,
              const std::function<void()>& before_delivering = {});

  // Datagrams the kernel dropped: other channels (the filter) and overflow.
  std::uint64_t kernel_drops() const;

 private:
  static constexpr int kBatch = 16;
  static constexpr std::size_t kDatagramBytes = 65536;

  int fd_ = -1;
  std::vector<char> buffers_;  // kBatch datagrams
};

}  // namespace ubersim
