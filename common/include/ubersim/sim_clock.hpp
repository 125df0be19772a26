#pragma once
// Follows simulation time as physics reports it on SIM_STATE. The emulators
// act in sim time (docs/design.md, Time), so they all need the same answers: what
// time is it, did that message go backwards (out of order: skip it), or did the
// world reset (time jumped back to near zero at step 0..few: start over).
#include <cmath>
#include <cstdint>

namespace ubersim {

class SimClock {
 public:
  enum class Update { Advanced, Reset, Rejected };

  // Beyond any game or batch run (about 31 years): a later time comes only from
  // a forged or corrupt message. Bounding it here keeps every schedule that
  // counts instants in sim time (camera frames at 1/frame_rate, radio cycles)
  // inside a 64-bit count.
  static constexpr double kMaxSimTime = 1e9;  // s

  // A time physics could have sent: finite, not negative, at most kMaxSimTime.
  static bool valid_time(double sim_time) {
    return std::isfinite(sim_time) && sim_time >= 0 && sim_time <= kMaxSimTime;
  }

  // Feed each SIM_STATE's (sim_time, step). Rejected: non-finite, negative,
  // beyond kMaxSimTime, or older than what was seen (an out-of-order message),
  // and the clock is unchanged.
  Update update(double sim_time, std::int64_t step) {
    if (!valid_time(sim_time) || step < 0) return Update::Rejected;
    if (!started_) {
      started_ = true;
      time_ = sim_time;
      step_ = step;
      return Update::Advanced;
    }
    if (step < step_ || sim_time < time_) {
      // Physics restarts the step count at a reset; anything else that goes
      // backwards is a stale or reordered message.
      if (step <= kResetStepWindow && step < step_) {
        time_ = sim_time;
        step_ = step;
        return Update::Reset;
      }
      return Update::Rejected;
    }
    time_ = sim_time;
    step_ = step;
    return Update::Advanced;
  }

  bool started() const { return started_; }
  double now() const { return time_; }
  std::int64_t step() const { return step_; }

 private:
  static constexpr std::int64_t kResetStepWindow = 2;
  bool started_ = false;
  double time_ = 0;
  std::int64_t step_ = 0;
};

}  // namespace ubersim
