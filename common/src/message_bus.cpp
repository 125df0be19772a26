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
  address_ = parse_lcm_udpm_url(url);
  if (address_) receiver_ = std::make_unique<LcmUdpmReceiver>(*address_);
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

void MessageBus::add_unhurried_subscription(std::unique_ptr<Subscription> subscription,
                                            const std::string& channel) {
  if (!is_plain_channel_name(channel)) {
    throw std::invalid_argument("an unhurried subscription needs a plain channel name, not '" +
                                channel + "'");
  }
  if (!receiver_) {  // memq://, file://: LCM delivers it like any other
    add_subscription(std::move(subscription), channel, 1000);
    return;
  }
  if (!unhurried_receiver_) unhurried_receiver_ = std::make_unique<LcmUdpmReceiver>(*address_);
  unhurried_[channel].push_back(subscription.get());
  std::set<std::string> channels;
  for (const auto& entry : unhurried_) channels.insert(entry.first);
  unhurried_receiver_->want_channels(channels);
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

LcmUdpmReceiver::Deliver MessageBus::deliver_to(const DirectSubscriptions& subscriptions) {
  return [&subscriptions](const char* channel, const void* data, std::size_t size,
                          std::int64_t received) {
    const auto found = subscriptions.find(std::string_view(channel));
    if (found == subscriptions.end()) return;  // only while the filter could not be attached
    for (Subscription* subscription : found->second) {
      subscription->deliver(found->first, data, size, received);
    }
  };
}

LcmUdpmReceiver::Drop MessageBus::count_drop() {
  return [this](const char* why, std::size_t size) {
    bad_input_.warn(
        std::string("lcm:") + why,
        "dropped a datagram of " + std::to_string(size) + " bytes (" + why +
            (std::string(why) == "fragment" ? ": messages over 64 KB are not received on this bus)"
                                            : ")"));
  };
}

int MessageBus::handle_direct(int budget) {
  if (!receiver_ || budget <= 0) return 0;
  const LcmUdpmReceiver::Drop drop = count_drop();
  int unhurried_budget = budget;
  bool unhurried_read = false;
  // After each batch of the polled socket is read and before it is
  // delivered: whatever was sent before a message of that batch is on the
  // unhurried socket by then, and is delivered first.
  const auto read_unhurried = [&] {
    unhurried_read = true;
    if (!unhurried_receiver_ || unhurried_budget <= 0) return;
    unhurried_budget -=
        unhurried_receiver_->receive(unhurried_budget, deliver_to(unhurried_), drop);
  };
  const int prompt = receiver_->receive(budget, deliver_to(direct_), drop, read_unhurried);
  if (!unhurried_read) read_unhurried();
  return prompt + (budget - unhurried_budget);
}

int MessageBus::handle_unhurried(int budget) {
  if (!unhurried_receiver_ || budget <= 0) return 0;
  return unhurried_receiver_->receive(budget, deliver_to(unhurried_), count_drop());
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
  // A wait that ends with nothing on the polled doors still reads the
  // unhurried subscriptions: the loop acts after it.
  if (ready <= 0) return handle_unhurried(kMaxMessagesPerWakeup);
  // The watched doors first: their input waited in their own queues (a
  // socket, DDS's reader cache) while LCM's waited in its own.
  for (std::size_t i = 0; i < watches_.size(); ++i) {
    if ((poll_fds_[i + 2].revents & (POLLIN | POLLERR | POLLHUP)) != 0) watches_[i].on_readable();
  }
  const bool direct_ready = (poll_fds_[0].revents & POLLIN) != 0;
  const bool lcm_ready = (poll_fds_[1].revents & POLLIN) != 0;
  if (!direct_ready && !lcm_ready) return handle_unhurried(kMaxMessagesPerWakeup);
  return handle_pending();
}

}  // namespace ubersim
