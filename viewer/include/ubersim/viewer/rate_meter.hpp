#pragma once
// Messages per second of wall time on one channel, measured over windows of
// about a second (what a person watching the page wants to read).
#include <chrono>
#include <cstdint>

namespace ubersim::viewer {

class RateMeter {
 public:
  using Clock = std::chrono::steady_clock;
  explicit RateMeter(Clock::duration window = std::chrono::seconds(1)) : window_(window) {}

  void count(Clock::time_point now) {
    update(now);
    ++events_;
  }
  // The rate over the last complete window; 0 once nothing arrived for a window.
  double rate(Clock::time_point now) {
    update(now);
    return rate_;
  }

 private:
  void update(Clock::time_point now) {
    if (!started_) {
      started_ = true;
      window_start_ = now;
      return;
    }
    const auto elapsed = now - window_start_;
    if (elapsed < window_) return;
    rate_ = static_cast<double>(events_) / std::chrono::duration<double>(elapsed).count();
    events_ = 0;
    window_start_ = now;
  }

  Clock::duration window_;
  Clock::time_point window_start_{};
  std::uint64_t events_ = 0;
  double rate_ = 0;
  bool started_ = false;
};

}  // namespace ubersim::viewer
