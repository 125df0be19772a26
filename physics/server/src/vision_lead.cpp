#include "ubersim/physics/vision_lead.hpp"

#include <cmath>

#include "ubersim/logging.hpp"
#include "ubersim/vision_backpressure.hpp"

namespace ubersim::physics {

void VisionLead::on_schedule(const vision_schedule_t& schedule, Clock::time_point wall) {
  heard_ = true;
  last_heard_ = wall;
  silent_ = false;
  // Step -1: listening, no state seen yet. The latest counts, not the
  // greatest: after a reset the vision's time starts again from 0 too.
  acknowledged_ = schedule.step < 0 || !std::isfinite(schedule.t_state)
                      ? -std::numeric_limits<double>::infinity()
                      : schedule.t_state;
}

bool VisionLead::holds(double sim_time, double dt, Clock::time_point wall) {
  if (!heard_) return false;
  if (wall - last_heard_ > kVisionSilence) {
    if (!silent_) {
      silent_ = true;
      ++silences_;
      spdlog::warn(
          "the vision emulator has said nothing for {} s: physics runs on without waiting for it "
          "(its frames may be lost)",
          std::chrono::duration_cast<std::chrono::seconds>(kVisionSilence).count());
    }
    return false;
  }
  return sim_time + dt * 1e-6 >= acknowledged_ + kVisionLead;
}

}  // namespace ubersim::physics
