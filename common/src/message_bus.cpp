#include "ubersim/message_bus.hpp"

#include <cerrno>
#include <cstring>
#include <ctime>

#include "ubersim/shutdown.hpp"

namespace ubersim {

MessageBus::MessageBus(const std::string& url) : lcm_(url) {
  if (!lcm_.good()) throw std::runtime_error("cannot open LCM at '" + url + "'");
  poll_fds_.push_back({lcm_.getFileno(), POLLIN, 0});
  poll_fds_.push_back({-1, POLLIN, 0});  // the shutdown signal, when a wait is given one
}

void MessageBus::add_subscription(lcm::Subscription* raw, const std::string& channel,
                                  int queue_capacity) {
  if (raw == nullptr) throw std::runtime_error("cannot subscribe to " + channel);
  raw->setQueueCapacity(queue_capacity);
}

void MessageBus::publish_encoded(const std::string& channel, const void* data, std::size_t size) {
  lcm_.publish(channel, data, static_cast<unsigned int>(size));
}

void MessageBus::watch(int fd, std::function<void()> on_readable) {
  watches_.push_back({fd, std::move(on_readable)});
  poll_fds_.insert(poll_fds_.end() - 1, pollfd{fd, POLLIN, 0});
}

void MessageBus::subscribe_raw(const std::string& channel_regex, RawHandler handler,
                               int queue_capacity) {
  auto subscription = std::make_unique<RawSubscription>();
  subscription->handler = std::move(handler);
  add_subscription(lcm_.subscribe(channel_regex, &RawSubscription::on_message, subscription.get()),
                   channel_regex, queue_capacity);
  subscriptions_.push_back(std::move(subscription));
}

int MessageBus::handle_pending() {
  int handled = 0;
  while (handled < kMaxMessagesPerWakeup && lcm_.handleTimeout(0) > 0) ++handled;
  return handled;
}

int MessageBus::wait_and_handle(int timeout_ms, const ShutdownSignal* shutdown) {
  const timespec timeout{timeout_ms / 1000, static_cast<long>(timeout_ms % 1000) * 1000000L};
  return wait(timeout_ms < 0 ? nullptr : &timeout, shutdown);
}

int MessageBus::wait_until_and_handle(Clock::time_point deadline, const ShutdownSignal* shutdown) {
  const auto left = deadline - Clock::now();
  const auto ns =
      left > Clock::duration::zero() ? std::chrono::nanoseconds(left).count() : std::int64_t{0};
  const timespec timeout{static_cast<time_t>(ns / 1000000000), static_cast<long>(ns % 1000000000)};
  return wait(&timeout, shutdown);
}

int MessageBus::wait(const timespec* timeout, const ShutdownSignal* shutdown) {
  poll_fds_.back().fd = shutdown != nullptr ? shutdown->fd() : -1;
  for (pollfd& fd : poll_fds_) fd.revents = 0;
  const int ready = ::ppoll(poll_fds_.data(), poll_fds_.size(), timeout, nullptr);
  if (ready < 0 && errno != EINTR) {
    throw std::runtime_error(std::string("poll: ") + std::strerror(errno));
  }
  if (ready <= 0) return 0;
  // The watched doors first: their input waited in their own queues (a
  // socket, DDS's reader cache) while LCM's waited in its own.
  for (std::size_t i = 0; i < watches_.size(); ++i) {
    if ((poll_fds_[i + 1].revents & (POLLIN | POLLERR | POLLHUP)) != 0) watches_[i].on_readable();
  }
  return (poll_fds_.front().revents & POLLIN) != 0 ? handle_pending() : 0;
}

}  // namespace ubersim
