#pragma once
// Typed publish/subscribe over one LCM instance. LCM 1.3.1 has no lambda
// subscribe and prints-and-drops undecodable messages on its own; here every
// subscription decodes itself, so a malformed message is counted, logged
// (throttled) and dropped, and a handler is any callable.
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "ubersim/logging.hpp"

namespace ubersim {

class ShutdownSignal;

class MessageBus {
 public:
  // Throws std::runtime_error when LCM cannot open the URL.
  explicit MessageBus(const std::string& url);
  MessageBus(const MessageBus&) = delete;
  MessageBus& operator=(const MessageBus&) = delete;

  template <class Msg>
  void subscribe(const std::string& channel, std::function<void(const Msg&)> handler,
                 int queue_capacity = 1000);

  // Every message on the channels `channel_regex` matches, undecoded (for
  // recorders): channel, bytes, size, receive time (us since the epoch).
  using RawHandler =
      std::function<void(const std::string&, const void*, std::size_t, std::int64_t)>;
  void subscribe_raw(const std::string& channel_regex, RawHandler handler,
                     int queue_capacity = 100000);

  template <class Msg>
  void publish(const std::string& channel, const Msg& message) {
    lcm_.publish(channel, &message);
  }

  // Handles every message already waiting; returns how many.
  int handle_pending();
  // Waits up to timeout_ms for a message (or the shutdown signal), then handles
  // what is waiting. Returns how many messages were handled.
  int wait_and_handle(int timeout_ms, const ShutdownSignal* shutdown = nullptr);

  std::uint64_t malformed_count() const { return bad_input_.total(); }
  ThrottledLog& bad_input() { return bad_input_; }
  lcm::LCM& lcm() { return lcm_; }

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
      int used = -1;
      try {
        used = message.decode(buffer->data, 0, static_cast<int>(buffer->data_size));
      } catch (const std::exception&) {
        // lcm-gen's decode resizes arrays to the length the bytes claim before
        // reading them: a negative or huge length throws length_error/bad_alloc.
        used = -1;
      }
      if (used < 0 || static_cast<uint32_t>(used) != buffer->data_size) {
        bus->bad_input_.warn(
            "decode:" + channel,
            "dropped a message on " + channel + " that does not decode as " + Msg::getTypeName());
        return;
      }
      handler(message);
    }
  };

  struct RawSubscription : Subscription {
    RawHandler handler;
    void on_message(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
      handler(channel, buffer->data, buffer->data_size, buffer->recv_utime);
    }
  };

  lcm::LCM lcm_;
  ThrottledLog bad_input_;
  std::vector<std::unique_ptr<Subscription>> subscriptions_;
};

template <class Msg>
void MessageBus::subscribe(const std::string& channel, std::function<void(const Msg&)> handler,
                           int queue_capacity) {
  auto subscription = std::make_unique<TypedSubscription<Msg>>();
  subscription->bus = this;
  subscription->handler = std::move(handler);
  lcm::Subscription* raw =
      lcm_.subscribe(channel, &TypedSubscription<Msg>::on_message, subscription.get());
  if (raw == nullptr) throw std::runtime_error("cannot subscribe to " + channel);
  raw->setQueueCapacity(queue_capacity);
  subscriptions_.push_back(std::move(subscription));
}

}  // namespace ubersim
