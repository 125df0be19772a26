#include "ubersim/physics/stepping_clock.hpp"

#include "ubersim/process_cpu.hpp"

namespace ubersim::physics {

void SteppingClock::step_begins() {
  if (in_run_) return;
  run_start_ = thread_cpu_seconds();
  in_run_ = true;
}

void SteppingClock::run_ends() {
  if (!in_run_) return;
  seconds_ += thread_cpu_seconds() - run_start_;
  in_run_ = false;
}

}  // namespace ubersim::physics
