// Sleeps (docs/timeshim.md, "What it intercepts"): they end when sim time
// reaches their deadline, which the controller decides.
#include <errno.h>
#include <semaphore.h>
#include <time.h>
#include <unistd.h>

#include "det_sync.hpp"
#include "runtime.hpp"

namespace shim = ubersim::timeshim::shim;
using ubersim::timeshim::kNoDeadline;
using ubersim::timeshim::ShimCall;
using ubersim::timeshim::ThreadState;

namespace {

// Sleeps `duration_ns` of sim time from this thread's now; on EINTR writes
// what was left to *remaining (when given). Returns 0 or EINTR.
int sleep_for(std::int64_t duration_ns, ShimCall call, timespec* remaining) {
  const std::int64_t deadline = shim::deadline_after(shim::view_now(), duration_ns);
  if (duration_ns <= 0) {
    shim::charge_call();
    return 0;
  }
  const int result = shim::sleep_until(deadline, call);
  if (result == EINTR && remaining != nullptr) {
    *remaining = shim::to_timespec(deadline - shim::view_now());
  }
  return result;
}

bool valid_time(const timespec* t) {
  return t != nullptr && t->tv_nsec >= 0 && t->tv_nsec < shim::kNsPerSecond && t->tv_sec >= 0;
}

}  // namespace

extern "C" {

__attribute__((visibility("default"))) int nanosleep(const timespec* duration,
                                                     timespec* remaining) {
  if (shim::segment() == nullptr) {
    static const auto real = shim::next_symbol<int (*)(const timespec*, timespec*)>("nanosleep");
    return real(duration, remaining);
  }
  if (!valid_time(duration)) {
    errno = EINVAL;
    return -1;
  }
  const int result = sleep_for(shim::to_ns(*duration), ShimCall::Nanosleep, remaining);
  if (result == 0) return 0;
  errno = result;
  return -1;
}

__attribute__((visibility("default"))) int clock_nanosleep(clockid_t clock, int flags,
                                                           const timespec* request,
                                                           timespec* remaining) {
  std::int64_t offset = 0;
  if (shim::segment() == nullptr || !shim::sim_clock(clock, &offset)) {
    static const auto real =
        shim::next_symbol<int (*)(clockid_t, int, const timespec*, timespec*)>("clock_nanosleep");
    return real(clock, flags, request, remaining);
  }
  if (!valid_time(request)) return EINVAL;
  if ((flags & TIMER_ABSTIME) == 0) {
    return sleep_for(shim::to_ns(*request), ShimCall::ClockNanosleep, remaining);
  }
  const std::int64_t deadline = shim::to_ns(*request) - offset;
  if (deadline <= shim::view_now()) {
    shim::charge_call();
    return 0;
  }
  return shim::sleep_until(deadline, ShimCall::ClockNanosleep);
}

__attribute__((visibility("default"))) int usleep(useconds_t microseconds) {
  if (shim::segment() == nullptr) {
    static const auto real = shim::next_symbol<int (*)(useconds_t)>("usleep");
    return real(microseconds);
  }
  const int result =
      sleep_for(static_cast<std::int64_t>(microseconds) * 1000, ShimCall::Usleep, nullptr);
  if (result == 0) return 0;
  errno = result;
  return -1;
}

__attribute__((visibility("default"))) unsigned int sleep(unsigned int seconds) {
  if (shim::segment() == nullptr) {
    static const auto real = shim::next_symbol<unsigned int (*)(unsigned int)>("sleep");
    return real(seconds);
  }
  timespec remaining{};
  if (sleep_for(static_cast<std::int64_t>(seconds) * shim::kNsPerSecond, ShimCall::Sleep,
                &remaining) == 0) {
    return 0;
  }
  return static_cast<unsigned int>(remaining.tv_sec + (remaining.tv_nsec > 0 ? 1 : 0));
}

}  // extern "C"

namespace {

int real_sem_clockwait(sem_t* semaphore, clockid_t clock, const timespec* limit) {
  static const auto real =
      shim::next_symbol<int (*)(sem_t*, clockid_t, const timespec*)>("sem_clockwait");
  return real(semaphore, clock, limit);
}

// A semaphore wait until a sim deadline: sem_wait interrupted by the wake
// signal (it never restarts after a handler) when the deadline passes.
int sem_wait_until(sem_t* semaphore, std::int64_t deadline) {
  if (shim::deterministic()) return shim::det_sem_wait(semaphore, deadline);
  if (sem_trywait(semaphore) == 0) return 0;
  if (errno != EAGAIN) return -1;
  if (deadline <= shim::view_now()) {
    shim::charge_call();
    errno = ETIMEDOUT;
    return -1;
  }
  bool timed_out = false;
  const int result = shim::wait_until(deadline, ShimCall::SemTimedwait, ThreadState::WaitingSem,
                                      nullptr, &timed_out, [semaphore](const sigset_t* mask) {
                                        sigset_t saved{};
                                        pthread_sigmask(SIG_SETMASK, mask, &saved);
                                        const timespec limit = shim::wall_liveness_deadline();
                                        const int waited =
                                            real_sem_clockwait(semaphore, CLOCK_MONOTONIC, &limit);
                                        const int error = errno;
                                        pthread_sigmask(SIG_SETMASK, &saved, nullptr);
                                        errno = error;
                                        if (waited == 0) return 1;
                                        return error == ETIMEDOUT ? 0 : -1;
                                      });
  if (timed_out) {
    if (sem_trywait(semaphore) == 0) return 0;
    errno = ETIMEDOUT;
    return -1;
  }
  return result > 0 ? 0 : result;
}

}  // namespace

extern "C" {

__attribute__((visibility("default"))) int sem_timedwait(sem_t* semaphore,
                                                         const timespec* deadline) {
  std::int64_t offset = 0;
  if (shim::segment() == nullptr) {
    static const auto real = shim::next_symbol<int (*)(sem_t*, const timespec*)>("sem_timedwait");
    return real(semaphore, deadline);
  }
  if (!valid_time(deadline)) {
    errno = EINVAL;
    return -1;
  }
  shim::sim_clock(CLOCK_REALTIME, &offset);
  return sem_wait_until(semaphore, shim::to_ns(*deadline) - offset);
}

__attribute__((visibility("default"))) int sem_clockwait(sem_t* semaphore, clockid_t clock,
                                                         const timespec* deadline) {
  std::int64_t offset = 0;
  if (shim::segment() == nullptr || !shim::sim_clock(clock, &offset)) {
    static const auto real =
        shim::next_symbol<int (*)(sem_t*, clockid_t, const timespec*)>("sem_clockwait");
    return real(semaphore, clock, deadline);
  }
  if (!valid_time(deadline)) {
    errno = EINVAL;
    return -1;
  }
  return sem_wait_until(semaphore, shim::to_ns(*deadline) - offset);
}

}  // extern "C"
