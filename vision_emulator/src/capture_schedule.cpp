#include "ubersim/vision/capture_schedule.hpp"

#include <algorithm>
#include <cmath>

namespace ubersim::vision {

std::optional<CaptureSchedule::Capture> CaptureSchedule::on_state(double sim_time) {
  // Index of the last instant at or before sim_time (-1 when none yet).
  const auto last_due =
      static_cast<std::int64_t>(std::floor((sim_time + kTolerance - phase_) * frame_rate_));
  if (!started_) {
    // The first state seen (at start-up or after a reset) is captured if an
    // instant falls on it; instants before it were never ours to serve.
    started_ = true;
    next_index_ = std::max<std::int64_t>(
        0, static_cast<std::int64_t>(std::ceil((sim_time - kTolerance - phase_) * frame_rate_)));
  }
  // Guard the floor() above against rounding: instant(last_due) must be due.
  std::int64_t last = last_due;
  while (last >= next_index_ && instant(last) > sim_time + kTolerance) --last;
  if (last < next_index_) return std::nullopt;

  Capture capture;
  capture.missed_instants = last - next_index_;
  capture.frame_number = next_frame_number_ + capture.missed_instants;
  next_frame_number_ = capture.frame_number + 1;
  next_index_ = last + 1;
  return capture;
}

}  // namespace ubersim::vision
