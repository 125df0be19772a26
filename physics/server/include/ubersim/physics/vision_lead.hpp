#pragma once
// As fast as possible outside sync mode, physics never starts a step more than
// kVisionLead of sim time after the last state the vision emulator
// acknowledged (the t_state of its SIM_VISION_SCHEDULE), so that no state,
// and no frame, is lost in its socket (docs/vision.md, "As fast as possible").
// A part of physics' shell: it is handed the wall time of each call.
#include <chrono>
#include <cstdint>
#include <limits>
#include <ubersim/vision_schedule_t.hpp>

namespace ubersim::physics {

class VisionLead {
 public:
  using Clock = std::chrono::steady_clock;

  // The vision emulator listens, and how far it has got.
  void on_schedule(const vision_schedule_t& schedule, Clock::time_point wall);
  // Whether the step that starts at `sim_time` must wait for an
  // acknowledgement. False while no vision emulator is heard, or one fell
  // silent for kVisionSilence (logged once per silence).
  bool holds(double sim_time, double dt, Clock::time_point wall);
  // A vision emulator has spoken (it listens).
  bool heard() const { return heard_; }
  // Times it fell silent while physics was waiting for it.
  std::int64_t silences() const { return silences_; }

 private:
  bool heard_ = false;
  // The sim time of the last state it acknowledged (-inf while it has seen
  // none), and when it last spoke.
  double acknowledged_ = -std::numeric_limits<double>::infinity();
  Clock::time_point last_heard_{};
  bool silent_ = false;
  std::int64_t silences_ = 0;
};

}  // namespace ubersim::physics
