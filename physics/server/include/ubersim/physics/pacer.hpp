#pragma once
// When the next physics step is due. Real time and speed factors follow an
// absolute schedule: step n (ending at sim time (n + 1) dt) is due at
// anchor + (n + 1 - anchor_step) dt / speed,
// so late wake-ups never add up to drift. The schedule restarts (re-anchors)
// on resume, reset, speed changes and when the machine cannot keep up. It
// reads no clock: every time point is handed in (the schedule starts with
// restart or set_speed).
#include <chrono>
#include <cstdint>

namespace ubersim::physics {

class Pacer {
 public:
  using Clock = std::chrono::steady_clock;

  // speed: > 0 times real time, 0 as fast as possible, < 0 lockstep.
  Pacer(double dt, double speed, double max_lag_seconds);

  void set_speed(double speed, Clock::time_point now, std::int64_t step);
  void restart(Clock::time_point now, std::int64_t step);

  double speed() const { return speed_; }
  bool lockstep() const { return speed_ < 0; }
  bool as_fast_as_possible() const { return speed_ == 0; }
  bool paced() const { return speed_ > 0; }

  // Paced modes: when step `step` may start.
  Clock::time_point due(std::int64_t step) const;
  // Paced modes: true (and re-anchored at `now`) when step `step` is later
  // than the allowed lag, i.e. the machine cannot keep up.
  bool restart_if_behind(Clock::time_point now, std::int64_t step);
  // Sim time ahead of the schedule (s, negative: behind), since the anchor.
  double drift(Clock::time_point now, std::int64_t step) const;

 private:
  double dt_;
  double speed_;
  Clock::duration max_lag_;
  Clock::time_point anchor_time_{};
  std::int64_t anchor_step_ = 0;
};

}  // namespace ubersim::physics
