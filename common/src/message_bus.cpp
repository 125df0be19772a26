#include "ubersim/message_bus.hpp"

#include <poll.h>

#include "ubersim/shutdown.hpp"

namespace ubersim {

MessageBus::MessageBus(const std::string& url) : lcm_(url) {
  if (!lcm_.good()) throw std::runtime_error("cannot open LCM at '" + url + "'");
}

void MessageBus::subscribe_raw(const std::string& channel_regex, RawHandler handler,
                               int queue_capacity) {
  auto subscription = std::make_unique<RawSubscription>();
  subscription->handler = std::move(handler);
  lcm::Subscription* raw =
      lcm_.subscribe(channel_regex, &RawSubscription::on_message, subscription.get());
  if (raw == nullptr) throw std::runtime_error("cannot subscribe to " + channel_regex);
  raw->setQueueCapacity(queue_capacity);
  subscriptions_.push_back(std::move(subscription));
}

int MessageBus::handle_pending() {
  int handled = 0;
  while (lcm_.handleTimeout(0) > 0) ++handled;
  return handled;
}

int MessageBus::wait_and_handle(int timeout_ms, const ShutdownSignal* shutdown) {
  pollfd fds[2] = {{lcm_.getFileno(), POLLIN, 0}, {-1, POLLIN, 0}};
  nfds_t count = 1;
  if (shutdown != nullptr) {
    fds[1].fd = shutdown->fd();
    count = 2;
  }
  const int ready = ::poll(fds, count, timeout_ms);
  if (ready <= 0 || !(fds[0].revents & POLLIN)) return 0;
  return handle_pending();
}

}  // namespace ubersim
