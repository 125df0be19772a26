#pragma once
// Holds items until sim time reaches their release time, then hands them out
// in order. Release times are made non-decreasing on insertion, so jitter can
// never reorder a stream (a real link or vision server delivers in order).
#include <deque>
#include <utility>
#include <vector>

namespace ubersim {

// A timed item is due at a state up to this much before its release time:
// sim times are sums of steps, so a release at a step's time may be a hair
// after that step's state (the radio's feedback; what waits for it).
inline constexpr double kReleaseEpsilon = 1e-6;  // s

template <class T>
class DelayLine {
 public:
  // Returns the release time actually used (>= the previous one).
  double push(double release_time, T item) {
    if (!items_.empty() && release_time < items_.back().first) release_time = items_.back().first;
    items_.emplace_back(release_time, std::move(item));
    return release_time;
  }

  // Everything due at `now`, oldest first.
  std::vector<std::pair<double, T>> pop_due(double now) {
    std::vector<std::pair<double, T>> due;
    while (!items_.empty() && items_.front().first <= now) {
      due.push_back(std::move(items_.front()));
      items_.pop_front();
    }
    return due;
  }

  void clear() { items_.clear(); }
  std::vector<double> release_times() const {
    std::vector<double> times;
    for (const auto& item : items_) times.push_back(item.first);
    return times;
  }
  // Release time of the oldest item (the line must not be empty).
  double front_release() const { return items_.front().first; }
  bool empty() const { return items_.empty(); }
  std::size_t size() const { return items_.size(); }

 private:
  std::deque<std::pair<double, T>> items_;
};

}  // namespace ubersim
