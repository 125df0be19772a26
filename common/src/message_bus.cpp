#include "ubersim/message_bus.hpp"

#include <cerrno>
#include <cstring>
#include <ctime>
#include <optional>
#include <set>
#include <string_view>

#include "ubersim/lcm_channel_filter.hpp"
#include "ubersim/lcm_udpm_receiver.hpp"
#include "ubersim/shutdown.hpp"

namespace ubersim {

MessageBus::MessageBus(const std::string& url) : lcm_(url) {
  if (!lcm_.good()) throw std::runtime_error("cannot open LCM at '" + url + "'");
  if (const std::optional<LcmUdpmAddress> address = parse_lcm_udpm_url(url)) {
    receiver_ = std::make_unique<LcmUdpmReceiver>(*address);
  }
  poll_fds_.push_back({receiver_ ? receiver_->fd() : -1, POLLIN, 0});
  poll_fds_.push_back({-1, POLLIN, 0});  // LCM's, once a subscription goes through it
  poll_fds_.push_back({-1, POLLIN, 0});  // the shutdown signal, when a wait is given one
}

void MessageBus::add_subscription(std::unique_ptr<Subscription> subscription,
                                  const std::string& channel, int queue_capacity) {
  if (receiver_ && is_plain_channel_name(channel)) {
    direct_[channel].push_back(subscription.get());
    std::set<std::string> channels;
    for (const auto& entry : direct_) channels.insert(entry.first);
    // After the handler is in place: a datagram the old filter dropped in
    // between arrived before the subscription, which LCM would not deliver.
    receiver_->want_channels(channels);
  } else {
    lcm::Subscription* raw =
        lcm_.subscribe(channel, &Subscription::on_lcm_message, subscription.get());
    if (raw == nullptr) throw std::runtime_error("cannot subscribe to " + channel);
    raw->setQueueCapacity(queue_capacity);
    if (!lcm_receives_) {
      lcm_receives_ = true;
      poll_fds_[1].fd = lcm_.getFileno();  // starts LCM's receive thread
    }
  }
  subscriptions_.push_back(std::move(subscription));
}

std::uint64_t MessageBus::kernel_drops() const {
  return receiver_ ? receiver_->kernel_drops() : 0;
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
  add_subscription(std::move(subscription), channel_regex, queue_capacity);
}

int MessageBus::handle_direct(int budget) {
  if (!receiver_ || budget <= 0) return 0;
  return receiver_->receive(
      budget,
      [this](const char* channel, const void* data, std::size_t size, std::int64_t received) {
        const auto found = direct_.find(std::string_view(channel));
        if (found == direct_.end()) return;  // only while the filter could not be attached
        for (Subscription* subscription : found->second) {
          subscription->deliver(found->first, data, size, received);
        }
      },
      [this](const char* why, std::size_t size) {
        bad_input_.warn(std::string("lcm:") + why,
                        "dropped a datagram of " + std::to_string(size) + " bytes (" + why +
                            (std::string(why) == "fragment"
                                 ? ": messages over 64 KB are not received on this bus)"
                                 : ")"));
      });
}

int MessageBus::handle_pending() {
  int handled = handle_direct(kMaxMessagesPerWakeup);
  if (lcm_receives_) {
    while (handled < kMaxMessagesPerWakeup && lcm_.handleTimeout(0) > 0) ++handled;
  }
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
    if ((poll_fds_[i + 2].revents & (POLLIN | POLLERR | POLLHUP)) != 0) watches_[i].on_readable();
  }
  const bool direct_ready = (poll_fds_[0].revents & POLLIN) != 0;
  const bool lcm_ready = (poll_fds_[1].revents & POLLIN) != 0;
  if (!direct_ready && !lcm_ready) return 0;
  return handle_pending();
}

}  // namespace ubersim
