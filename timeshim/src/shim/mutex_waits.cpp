// Timed mutex locks (pthread_mutex_timedlock, pthread_mutex_clocklock;
// std::timed_mutex; docs/timeshim.md, "What it intercepts"): the deadline is
// sim time. glibc's own timed lock restarts its futex wait after a signal, so
// for a plain mutex (the default kind, std::timed_mutex's) the shim waits on
// the mutex's futex itself, with glibc's protocol (lock word 2: locked with
// waiters), where the controller's wake signal can end the wait; other kinds
// wait in slices of wall time.
#include <linux/futex.h>
#include <pthread.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cerrno>

#include "det_sync.hpp"
#include "runtime.hpp"

namespace shim = ubersim::timeshim::shim;
using ubersim::timeshim::ShimCall;
using ubersim::timeshim::ThreadState;

namespace {

constexpr int kPlainMutex = 0;  // PTHREAD_MUTEX_TIMED_NP, without robust or PI bits
constexpr timespec kSlice{0, 5000000};

int real_trylock(pthread_mutex_t* mutex) {
  static const auto next = shim::next_symbol<int (*)(pthread_mutex_t*)>("pthread_mutex_trylock");
  return next(mutex);
}

int real_clocklock(pthread_mutex_t* mutex, clockid_t clock, const timespec* limit) {
  static const auto next = shim::next_symbol<int (*)(pthread_mutex_t*, clockid_t, const timespec*)>(
      "pthread_mutex_clocklock");
  return next(mutex, clock, limit);
}

// glibc's slow path of a plain mutex: take it marked "with waiters" (2), so
// that its unlock wakes the others; owner and user count as glibc keeps them.
bool take_contended(pthread_mutex_t* mutex) {
  if (__atomic_exchange_n(&mutex->__data.__lock, 2, __ATOMIC_ACQUIRE) != 0) return false;
  mutex->__data.__owner = static_cast<int>(::syscall(SYS_gettid));
  ++mutex->__data.__nusers;
  return true;
}

// One wait for the mutex with the thread's mask `mask` (the wake signal let
// through): 1 when taken, 0 when the wall-time limit passed, -1 (EINTR) for
// a signal.
int wait_once(pthread_mutex_t* mutex, const sigset_t* mask) {
  if ((mutex->__data.__kind & 0x7f) != kPlainMutex) {
    const timespec slice_end = shim::to_timespec(shim::wall_monotonic_ns() + shim::to_ns(kSlice));
    return real_clocklock(mutex, CLOCK_MONOTONIC, &slice_end) == 0 ? 1 : 0;
  }
  if (take_contended(mutex)) return 1;
  sigset_t saved{};
  pthread_sigmask(SIG_SETMASK, mask, &saved);
  const long waited = ::syscall(SYS_futex, &mutex->__data.__lock, FUTEX_WAIT_PRIVATE, 2,
                                &shim::kLivenessCheck, nullptr, 0);
  const int error = errno;
  pthread_sigmask(SIG_SETMASK, &saved, nullptr);
  if (take_contended(mutex)) return 1;
  if (waited != 0 && error == EINTR) {
    errno = EINTR;
    return -1;
  }
  return 0;
}

int lock_until(pthread_mutex_t* mutex, std::int64_t deadline) {
  if (shim::deterministic()) return shim::det_mutex_lock(mutex, deadline);
  const int tried = real_trylock(mutex);
  if (tried != EBUSY) return tried;
  if (mutex->__data.__owner == static_cast<int>(::syscall(SYS_gettid))) return EDEADLK;
  if (deadline <= shim::view_now()) {
    shim::charge_call();
    return ETIMEDOUT;
  }
  bool timed_out = false;
  const int result =
      shim::wait_until(deadline, ShimCall::MutexLock, ThreadState::WaitingSem, nullptr, &timed_out,
                       [mutex](const sigset_t* mask) { return wait_once(mutex, mask); });
  if (timed_out) return real_trylock(mutex) == 0 ? 0 : ETIMEDOUT;
  return result > 0 ? 0 : errno;
}

bool valid_deadline(const timespec* t) {
  return t != nullptr && t->tv_nsec >= 0 && t->tv_nsec < shim::kNsPerSecond;
}

}  // namespace

extern "C" {

__attribute__((visibility("default"))) int pthread_mutex_timedlock(pthread_mutex_t* mutex,
                                                                   const timespec* deadline) {
  std::int64_t offset = 0;
  if (shim::segment() == nullptr) {
    static const auto next =
        shim::next_symbol<int (*)(pthread_mutex_t*, const timespec*)>("pthread_mutex_timedlock");
    return next(mutex, deadline);
  }
  if (!valid_deadline(deadline)) return EINVAL;
  shim::sim_clock(CLOCK_REALTIME, &offset);
  return lock_until(mutex, shim::to_ns(*deadline) - offset);
}

__attribute__((visibility("default"))) int pthread_mutex_clocklock(pthread_mutex_t* mutex,
                                                                   clockid_t clock,
                                                                   const timespec* deadline) {
  std::int64_t offset = 0;
  if (shim::segment() == nullptr || !shim::sim_clock(clock, &offset)) {
    return real_clocklock(mutex, clock, deadline);
  }
  if (!valid_deadline(deadline)) return EINVAL;
  return lock_until(mutex, shim::to_ns(*deadline) - offset);
}

}  // extern "C"
