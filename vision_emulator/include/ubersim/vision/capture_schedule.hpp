#pragma once
// When one camera captures, phase-locked to simulation time: at
// phase + n / frame_rate. Physics reports the world only at its steps, so a
// capture instant is served by the first step at or after it (within a
// microsecond, so that instants written in decimal, like a phase of
// 0.0041667 s for 1/240 s, still land on their step).
#include <cstdint>
#include <optional>

namespace ubersim::vision {

class CaptureSchedule {
 public:
  static constexpr double kTolerance = 1e-6;  // s

  CaptureSchedule(double frame_rate, double phase) : frame_rate_(frame_rate), phase_(phase) {}

  struct Capture {
    std::int64_t frame_number = 0;
    // Capture instants that passed with no sim state to serve them (lost
    // SIM_STATE messages, or physics slower than the camera); their frame
    // numbers are skipped, as a real camera's counter would show lost frames.
    std::int64_t missed_instants = 0;
  };

  // Feed the time of each new sim state; says whether this state is captured.
  std::optional<Capture> on_state(double sim_time);

  // After a reset of sim time: instants restart at the phase in the new
  // timeline; frame numbers keep increasing.
  void restart() { started_ = false; }

  double instant(std::int64_t index) const {
    return phase_ + static_cast<double>(index) / frame_rate_;
  }
  std::int64_t next_frame_number() const { return next_frame_number_; }
  // Once a state was seen: the next instant not yet captured.
  bool started() const { return started_; }
  double next_instant() const { return instant(next_index_); }
  std::int64_t next_index() const { return next_index_; }

 private:
  double frame_rate_;
  double phase_;
  bool started_ = false;
  std::int64_t next_index_ = 0;  // index of the next instant not yet captured
  std::int64_t next_frame_number_ = 0;
};

}  // namespace ubersim::vision
