#include "ubersim/physics/stepping_clock.hpp"

#include <time.h>

namespace ubersim::physics {
namespace {

double thread_cpu_seconds() {
  timespec t{};
  ::clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace

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
