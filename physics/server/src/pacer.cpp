#include "ubersim/physics/pacer.hpp"

namespace ubersim::physics {

Pacer::Pacer(double dt, double speed, double max_lag_seconds)
    : dt_(dt),
      speed_(speed),
      max_lag_(std::chrono::duration_cast<Clock::duration>(
          std::chrono::duration<double>(max_lag_seconds))) {}

void Pacer::set_speed(double speed, Clock::time_point now, std::int64_t step) {
  speed_ = speed;
  restart(now, step);
}

void Pacer::restart(Clock::time_point now, std::int64_t step) {
  anchor_time_ = now;
  anchor_step_ = step;
}

Pacer::Clock::time_point Pacer::due(std::int64_t step) const {
  // Step n takes sim time to (n + 1) dt: it runs when the wall clock gets there,
  // so published sim time never runs ahead of the wall clock.
  const double wall = static_cast<double>(step + 1 - anchor_step_) * dt_ / speed_;
  return anchor_time_ +
         std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(wall));
}

bool Pacer::restart_if_behind(Clock::time_point now, std::int64_t step) {
  if (now - due(step) <= max_lag_) return false;
  restart(now, step);
  return true;
}

double Pacer::drift(Clock::time_point now, std::int64_t step) const {
  const double sim = static_cast<double>(step - anchor_step_) * dt_;
  const double wall = std::chrono::duration<double>(now - anchor_time_).count();
  return sim - wall * speed_;
}

}  // namespace ubersim::physics
