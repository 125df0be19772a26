#pragma once
// A test's listener that keeps the newest message on one channel, read from a
// bus of its own on the default LCM URL (the test's own port, see
// tests/run_isolated.sh), and waits until that message says what the test
// waits for.
#include <chrono>
#include <functional>
#include <optional>
#include <string>

#include "ubersim/common_options.hpp"
#include "ubersim/message_bus.hpp"

namespace ubersim::test {

template <class Msg>
class LatestMessage {
 public:
  explicit LatestMessage(const std::string& channel)
      : bus_(with_receive_buffer(default_lcm_url())) {
    bus_.subscribe<Msg>(channel, [this](const Msg& m) { latest_ = m; });
  }
  // True once a message for which done() holds came within timeout_s.
  bool wait_for(const std::function<bool(const Msg&)>& done, double timeout_s) {
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (std::chrono::steady_clock::now() < deadline) {
      bus_.wait_and_handle(20);
      if (latest_ && done(*latest_)) return true;
    }
    return false;
  }
  const std::optional<Msg>& latest() const { return latest_; }

 private:
  MessageBus bus_;
  std::optional<Msg> latest_;
};

}  // namespace ubersim::test
