#pragma once
// The one door to LCM. Typed publish/subscribe over one LCM instance, and the
// one wait of a process's loop: LCM's socket, the shutdown signal and any other
// file descriptor the process watches (a bridge's sockets, a wake pipe).
//
// Hostile input: every subscription decodes through decode_bounded (the
// schema's bounds first, so no datagram can make decode allocate more than it
// could hold); a malformed message is counted, logged (throttled) and dropped.
// One wakeup handles at most kMaxMessagesPerWakeup messages, so a flood on the
// bus cannot keep a loop from stepping, answering or seeing its shutdown; LCM
// bounds what waits (its receive ring buffer and each subscription's queue,
// where a flooded channel drops its own newest messages, not other channels').
#include <poll.h>

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "ubersim/bounded_decode.hpp"
#include "ubersim/logging.hpp"

namespace ubersim {

class ShutdownSignal;

class MessageBus {
 public:
  static constexpr int kMaxMessagesPerWakeup = 1000;
  using Clock = std::chrono::steady_clock;

  // Throws std::runtime_error when LCM cannot open the URL.
  explicit MessageBus(const std::string& url);
  MessageBus(const MessageBus&) = delete;
  MessageBus& operator=(const MessageBus&) = delete;

  template <class Msg>
  void subscribe(const std::string& channel, std::function<void(const Msg&)> handler,
                 int queue_capacity = 1000);

  // Every message on the channels `channel_regex` matches, undecoded: for
  // recorders and relays, which pass bytes on, and for consumers that must not
  // pay for a decode: channel, bytes, size, receive time (us since the epoch).
  using RawHandler =
      std::function<void(const std::string&, const void*, std::size_t, std::int64_t)>;
  void subscribe_raw(const std::string& channel_regex, RawHandler handler,
                     int queue_capacity = 100000);

  template <class Msg>
  void publish(const std::string& channel, const Msg& message) {
    lcm_.publish(channel, &message);
  }
  // Bytes already encoded (a buffer kept across publishes, or a relayed message).
  void publish_encoded(const std::string& channel, const void* data, std::size_t size);

  // Watches fd in every wait; on_readable runs once per wakeup in which fd is
  // readable and should do a bounded amount of work (read a bounded number of
  // datagrams), so that no door starves the others.
  void watch(int fd, std::function<void()> on_readable);

  // Handles up to kMaxMessagesPerWakeup messages already waiting; returns how many.
  int handle_pending();
  // Waits up to timeout_ms (or until the deadline) for a message, a watched fd
  // or the shutdown signal, then handles what is waiting. Returns how many LCM
  // messages were handled.
  int wait_and_handle(int timeout_ms, const ShutdownSignal* shutdown = nullptr);
  int wait_until_and_handle(Clock::time_point deadline, const ShutdownSignal* shutdown = nullptr);

  std::uint64_t malformed_count() const { return bad_input_.total(); }
  ThrottledLog& bad_input() { return bad_input_; }
  const ThrottledLog& bad_input() const { return bad_input_; }

 private:
  struct Subscription {
    virtual ~Subscription() = default;
  };
  template <class Msg>
  struct TypedSubscription : Subscription {
    MessageBus* bus = nullptr;
    std::function<void(const Msg&)> handler;
    void on_message(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
      Msg message;
      if (!decode_bounded(buffer->data, buffer->data_size, message)) {
        bus->bad_input_.warn("decode:" + channel, "dropped a message on " + channel + " (" +
                                                      std::to_string(buffer->data_size) +
                                                      " bytes) that does not " + "decode as " +
                                                      Msg::getTypeName());
        return;
      }
      handler(message);
    }
  };
  struct Watch {
    int fd;
    std::function<void()> on_readable;
  };

  void add_subscription(lcm::Subscription* raw, const std::string& channel, int queue_capacity);
  int wait(const timespec* timeout, const ShutdownSignal* shutdown);

  struct RawSubscription : Subscription {
    RawHandler handler;
    void on_message(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
      handler(channel, buffer->data, buffer->data_size, buffer->recv_utime);
    }
  };

  lcm::LCM lcm_;
  ThrottledLog bad_input_;
  std::vector<std::unique_ptr<Subscription>> subscriptions_;
  std::vector<Watch> watches_;
  std::vector<pollfd> poll_fds_;  // LCM, then one per watch, then the shutdown signal
};

template <class Msg>
void MessageBus::subscribe(const std::string& channel, std::function<void(const Msg&)> handler,
                           int queue_capacity) {
  auto subscription = std::make_unique<TypedSubscription<Msg>>();
  subscription->bus = this;
  subscription->handler = std::move(handler);
  add_subscription(lcm_.subscribe(channel, &TypedSubscription<Msg>::on_message, subscription.get()),
                   channel, queue_capacity);
  subscriptions_.push_back(std::move(subscription));
}

}  // namespace ubersim
