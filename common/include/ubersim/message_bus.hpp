#pragma once
// The one door to LCM. Typed publish/subscribe over one LCM instance, and the
// one wait of a process's loop: LCM's socket, the shutdown signal and any other
// file descriptor the process watches (a bridge's sockets, a wake pipe).
//
// Hostile input: every subscription decodes through decode_bounded (the
// schema's bounds first, so no datagram can make decode allocate more than it
// could hold); a malformed message is counted, logged (throttled) and dropped.
// One wakeup handles at most kMaxMessagesPerWakeup messages, so a flood on the
// bus cannot keep a loop from stepping, answering or seeing its shutdown. What
// waits is bounded by the kernel's socket buffer (direct subscriptions, below)
// or by LCM (its receive ring buffer and each subscription's queue, where a
// flooded channel drops its own newest messages, not other channels').
//
// On a udpm:// URL a subscription to a plain channel name is received by the
// process's own loop (lcm_udpm_receiver.hpp), not by LCM's receive thread,
// and the kernel drops the datagrams of channels no handler subscribes to
// (lcm_channel_filter.hpp): a process pays one wakeup per batch of the
// messages it reads, nothing for the others on the group. A subscription that
// is a regular expression (a recorder's ".*"), and every subscription on
// another provider (memq://, file://), goes through LCM as before.
#include <poll.h>

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "ubersim/bounded_decode.hpp"
#include "ubersim/lcm_udpm_receiver.hpp"
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

  // Like subscribe, but a message on this channel never wakes the loop: it
  // is read when the loop wakes for anything else (another message, a
  // watched fd, the end of a wait) or calls handle_pending, and always before
  // any message sent after it on a channel that does wake the loop. For input
  // whose effect is timed by its content (a command applied at its t_apply)
  // in a loop that wakes before that time anyway: each wakeup costs a
  // process 20-30 us in a VM. On another provider than udpm:// it is an
  // ordinary subscription. The channel must be a plain name.
  template <class Msg>
  void subscribe_unhurried(const std::string& channel, std::function<void(const Msg&)> handler);

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

  // True when this bus receives its plain-name subscriptions itself, with the
  // kernel filtering by channel.
  bool receives_directly() const { return receiver_ != nullptr; }
  // Datagrams the kernel dropped on the direct receiver's socket: channels
  // nobody here reads, and any overflow of its buffer.
  std::uint64_t kernel_drops() const;

  std::uint64_t malformed_count() const { return bad_input_.total(); }
  ThrottledLog& bad_input() { return bad_input_; }
  const ThrottledLog& bad_input() const { return bad_input_; }

 private:
  struct Subscription {
    virtual ~Subscription() = default;
    virtual void deliver(const std::string& channel, const void* data, std::size_t size,
                         std::int64_t received) = 0;
    void on_lcm_message(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
      deliver(channel, buffer->data, buffer->data_size, buffer->recv_utime);
    }
  };
  template <class Msg>
  struct TypedSubscription : Subscription {
    MessageBus* bus = nullptr;
    std::function<void(const Msg&)> handler;
    void deliver(const std::string& channel, const void* data, std::size_t size,
                 std::int64_t /*received*/) override {
      Msg message;
      if (!decode_bounded(data, size, message)) {
        bus->bad_input_.warn("decode:" + channel,
                             "dropped a message on " + channel + " (" + std::to_string(size) +
                                 " bytes) that does not " + "decode as " + Msg::getTypeName());
        return;
      }
      handler(message);
    }
  };
  struct Watch {
    int fd;
    std::function<void()> on_readable;
  };

  using DirectSubscriptions = std::map<std::string, std::vector<Subscription*>, std::less<>>;

  void add_subscription(std::unique_ptr<Subscription> subscription, const std::string& channel,
                        int queue_capacity);
  void add_unhurried_subscription(std::unique_ptr<Subscription> subscription,
                                  const std::string& channel);
  int handle_direct(int budget);
  // A wait that ended with nothing on the polled socket (its time was up, or
  // another door): only the unhurried socket can hold anything, so only it is
  // read (one system call less per timed wakeup; physics has ~40 a second).
  int handle_unhurried(int budget);
  LcmUdpmReceiver::Deliver deliver_to(const DirectSubscriptions& subscriptions);
  LcmUdpmReceiver::Drop count_drop();
  int wait(const timespec* timeout, const ShutdownSignal* shutdown);

  struct RawSubscription : Subscription {
    RawHandler handler;
    void deliver(const std::string& channel, const void* data, std::size_t size,
                 std::int64_t received) override {
      handler(channel, data, size, received);
    }
  };

  lcm::LCM lcm_;
  std::optional<LcmUdpmAddress> address_;      // udpm:// only
  std::unique_ptr<LcmUdpmReceiver> receiver_;  // udpm:// only
  // The plain-name subscriptions the receiver serves, by channel.
  DirectSubscriptions direct_;
  // A second socket on the group for the unhurried subscriptions, never
  // polled (created with the first of them).
  std::unique_ptr<LcmUdpmReceiver> unhurried_receiver_;
  DirectSubscriptions unhurried_;
  bool lcm_receives_ = false;  // a subscription went through LCM
  ThrottledLog bad_input_;
  std::vector<std::unique_ptr<Subscription>> subscriptions_;
  std::vector<Watch> watches_;
  // The receiver, LCM, then one per watch, then the shutdown signal (-1 when unused).
  std::vector<pollfd> poll_fds_;
};

template <class Msg>
void MessageBus::subscribe(const std::string& channel, std::function<void(const Msg&)> handler,
                           int queue_capacity) {
  auto subscription = std::make_unique<TypedSubscription<Msg>>();
  subscription->bus = this;
  subscription->handler = std::move(handler);
  add_subscription(std::move(subscription), channel, queue_capacity);
}

template <class Msg>
void MessageBus::subscribe_unhurried(const std::string& channel,
                                     std::function<void(const Msg&)> handler) {
  auto subscription = std::make_unique<TypedSubscription<Msg>>();
  subscription->bus = this;
  subscription->handler = std::move(handler);
  add_unhurried_subscription(std::move(subscription), channel);
}

}  // namespace ubersim
