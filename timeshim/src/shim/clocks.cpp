// Clock reads (docs/timeshim.md, "What it intercepts"): every clock id the
// shim serves reads sim time; CPU-time clocks go to the kernel.
#include <sys/time.h>
#include <time.h>

#include "runtime.hpp"

using ubersim::timeshim::shim::next_symbol;
using ubersim::timeshim::shim::read_clock;
using ubersim::timeshim::shim::segment;
using ubersim::timeshim::shim::sim_clock;
using ubersim::timeshim::shim::to_timespec;

namespace {
using ClockGettime = int (*)(clockid_t, timespec*);

int real_clock_gettime(clockid_t clock, timespec* result) {
  static const auto real = next_symbol<ClockGettime>("clock_gettime");
  return real(clock, result);
}

// Sim time on `clock` in ns, or false for a clock the kernel serves.
bool sim_reading(clockid_t clock, std::int64_t* ns) {
  std::int64_t offset = 0;
  if (segment() == nullptr || !sim_clock(clock, &offset)) return false;
  *ns = offset + read_clock();
  return true;
}
}  // namespace

extern "C" {

__attribute__((visibility("default"))) int clock_gettime(clockid_t clock,
                                                         timespec* result) noexcept {
  std::int64_t ns = 0;
  if (!sim_reading(clock, &ns)) return real_clock_gettime(clock, result);
  *result = to_timespec(ns);
  return 0;
}

__attribute__((visibility("default"))) int gettimeofday(timeval* result, void* zone) noexcept {
  std::int64_t ns = 0;
  if (!sim_reading(CLOCK_REALTIME, &ns)) {
    static const auto real = next_symbol<int (*)(timeval*, void*)>("gettimeofday");
    return real(result, zone);
  }
  const timespec t = to_timespec(ns);
  result->tv_sec = t.tv_sec;
  result->tv_usec = t.tv_nsec / 1000;
  return 0;
}

__attribute__((visibility("default"))) time_t time(time_t* result) noexcept {
  std::int64_t ns = 0;
  if (!sim_reading(CLOCK_REALTIME, &ns)) {
    static const auto real = next_symbol<time_t (*)(time_t*)>("time");
    return real(result);
  }
  const time_t seconds = to_timespec(ns).tv_sec;
  if (result != nullptr) *result = seconds;
  return seconds;
}

// C11's clock read; glibc's calls clock_gettime inside libc, past the shim.
__attribute__((visibility("default"))) int timespec_get(timespec* result, int base) noexcept {
  if (base != TIME_UTC) return 0;
  if (clock_gettime(CLOCK_REALTIME, result) != 0) return 0;
  return base;
}

}  // extern "C"
