// Timed condition variable waits (docs/timeshim.md, "What it intercepts"):
// the deadline is sim time. A signal cannot end glibc's pthread_cond_wait,
// so each process gets a helper thread that the controller wakes when a
// waiter's deadline passed; it broadcasts the waiter's condition variable (a
// spurious wakeup, which every caller must accept), and the waiter, seeing
// sim time past its deadline, returns ETIMEDOUT. CPython's GIL waits here.
#include <pthread.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>

#include "det_sync.hpp"
#include "runtime.hpp"
#include "timers.hpp"

namespace shim = ubersim::timeshim::shim;
using ubersim::timeshim::futex_wait;
using ubersim::timeshim::Header;
using ubersim::timeshim::ShimCall;
using ubersim::timeshim::ThreadSlot;
using ubersim::timeshim::ThreadState;

namespace {

std::atomic<pid_t> helper_pid{0};

// A due timer: its expirations up to now go to its eventfd (read returns
// their count, as a timerfd's does), and it is due again a period later.
void fire_timer(ThreadSlot& slot, std::int64_t now) {
  const std::int64_t deadline = slot.deadline_ns.load();
  const std::int64_t interval = slot.interval_ns.load();
  const std::uint64_t expirations =
      1 + (interval > 0 ? static_cast<std::uint64_t>((now - deadline) / interval) : 0);
  // The next deadline first: a reader woken by the write may ask for it.
  slot.deadline_ns.store(interval > 0 ? deadline + static_cast<std::int64_t>(expirations) * interval
                                      : ubersim::timeshim::kNoDeadline);
  if (slot.timer_kind.load() == static_cast<std::uint32_t>(ubersim::timeshim::TimerKind::Posix)) {
    shim::fire_posix_timer(slot, expirations);
  } else if (::write(slot.timer_fd.load(), &expirations, sizeof(expirations)) < 0) {
    // The counter is full; the program has not read it for 2^64 periods.
  }
  shim::notify();
}

void wake_due_waiters(Header& segment, pid_t pid) {
  const std::int64_t now = segment.sim_now_ns.load();
  for (auto& slot : used_slots(segment)) {
    if (slot.claim.load() == 0 || slot.pid.load() != pid) continue;
    if (slot.deadline_ns.load() > now) continue;
    if (slot.state.load() == static_cast<std::uint32_t>(ThreadState::Timer)) {
      fire_timer(slot, now);
      continue;
    }
    if (slot.state.load() != static_cast<std::uint32_t>(ThreadState::WaitingCond)) continue;
    // Pin, then look again: a waiter that left meanwhile may have destroyed
    // its condition variable; one that leaves later waits for the pin.
    slot.pin.store(1);
    if (slot.state.load() == static_cast<std::uint32_t>(ThreadState::WaitingCond)) {
      // The address is this process's own (the waiter's slot has its pid).
      // NOLINTNEXTLINE(performance-no-int-to-ptr)
      pthread_cond_broadcast(reinterpret_cast<pthread_cond_t*>(slot.cond_addr.load()));
    }
    slot.pin.store(0);
  }
}

void* run_helper(void* /*unused*/) {
  sigset_t all{};
  sigfillset(&all);
  pthread_sigmask(SIG_BLOCK, &all, nullptr);
  Header& segment = *shim::segment();
  ThreadSlot& slot = shim::own_slot();
  shim::set_state(slot, ThreadState::Helper, ShimCall::None, ubersim::timeshim::kNoDeadline);
  const pid_t pid = ::getpid();
  for (;;) {
    const std::uint32_t seq = slot.wake_seq.load();
    wake_due_waiters(segment, pid);
    futex_wait(slot.wake_seq, seq, -1);
  }
  return nullptr;
}

}  // namespace

namespace ubersim::timeshim::shim {

void ensure_helper() {
  const pid_t self = ::getpid();
  pid_t known = helper_pid.load();
  if (known == self || !helper_pid.compare_exchange_strong(known, self)) return;
  pthread_attr_t attributes;
  pthread_attr_init(&attributes);
  pthread_attr_setdetachstate(&attributes, PTHREAD_CREATE_DETACHED);
  pthread_attr_setstacksize(&attributes, std::size_t{64} * 1024);
  pthread_t thread;
  if (real_pthread_create(&thread, &attributes, run_helper, nullptr) == 0) {
    pthread_setname_np(thread, "timeshim-helper");
  }
  pthread_attr_destroy(&attributes);
}

}  // namespace ubersim::timeshim::shim

namespace {

using CondClockwaitFn = int (*)(pthread_cond_t*, pthread_mutex_t*, clockid_t, const timespec*);

int real_cond_clockwait(pthread_cond_t* cond, pthread_mutex_t* mutex, clockid_t clock,
                        const timespec* limit) {
  static const auto real = shim::next_symbol<CondClockwaitFn>("pthread_cond_clockwait");
  return real(cond, mutex, clock, limit);
}

int cond_wait_until(pthread_cond_t* cond, pthread_mutex_t* mutex, std::int64_t deadline) {
  if (shim::deterministic()) return shim::det_cond_wait(cond, mutex, deadline);
  const std::int64_t view_at_start = shim::view_now();
  if (deadline <= view_at_start) {
    shim::charge_call();
    return ETIMEDOUT;
  }
  shim::ensure_helper();
  ThreadSlot& slot = shim::own_slot();
  slot.cond_addr.store(reinterpret_cast<std::uint64_t>(cond));
  shim::set_state(slot, ThreadState::WaitingCond, ShimCall::CondTimedwait, deadline);
  int result = 0;
  if (shim::segment()->sim_now_ns.load() >= deadline) {
    result = ETIMEDOUT;
  } else {
    // Whatever wakes it (the program, or the helper at the deadline) is a
    // wakeup the caller checks its condition after; the wall-time limit only
    // checks that the controller still runs.
    for (;;) {
      const timespec limit = shim::wall_liveness_deadline();
      result = real_cond_clockwait(cond, mutex, CLOCK_MONOTONIC, &limit);
      if (result != ETIMEDOUT || shim::segment()->sim_now_ns.load() >= deadline) break;
      shim::exit_if_controller_gone();
    }
    if (result == 0 && shim::segment()->sim_now_ns.load() >= deadline) result = ETIMEDOUT;
  }
  shim::set_state(slot, ThreadState::Running, ShimCall::None, ubersim::timeshim::kNoDeadline);
  while (slot.pin.load() != 0) {
  }
  shim::after_block(view_at_start, result == ETIMEDOUT ? deadline : 0, ShimCall::CondTimedwait);
  return result;
}

// The clock a condition variable times out on: glibc keeps it in bit 1 of
// __wrefs (__PTHREAD_COND_CLOCK_MONOTONIC_MASK), set by pthread_condattr_setclock.
clockid_t clock_of(const pthread_cond_t* cond) {
  return (cond->__data.__wrefs & 2U) != 0 ? CLOCK_MONOTONIC : CLOCK_REALTIME;
}

}  // namespace

extern "C" {

__attribute__((visibility("default"))) int pthread_cond_timedwait(pthread_cond_t* cond,
                                                                  pthread_mutex_t* mutex,
                                                                  const timespec* deadline) {
  std::int64_t offset = 0;
  if (shim::segment() == nullptr || !shim::sim_clock(clock_of(cond), &offset)) {
    static const auto real =
        shim::next_symbol<int (*)(pthread_cond_t*, pthread_mutex_t*, const timespec*)>(
            "pthread_cond_timedwait");
    return real(cond, mutex, deadline);
  }
  if (deadline->tv_nsec < 0 || deadline->tv_nsec >= shim::kNsPerSecond) return EINVAL;
  return cond_wait_until(cond, mutex, shim::to_ns(*deadline) - offset);
}

__attribute__((visibility("default"))) int pthread_cond_clockwait(pthread_cond_t* cond,
                                                                  pthread_mutex_t* mutex,
                                                                  clockid_t clock,
                                                                  const timespec* deadline) {
  std::int64_t offset = 0;
  if (shim::segment() == nullptr || !shim::sim_clock(clock, &offset)) {
    static const auto real =
        shim::next_symbol<int (*)(pthread_cond_t*, pthread_mutex_t*, clockid_t, const timespec*)>(
            "pthread_cond_clockwait");
    return real(cond, mutex, clock, deadline);
  }
  if (deadline->tv_nsec < 0 || deadline->tv_nsec >= shim::kNsPerSecond) return EINVAL;
  return cond_wait_until(cond, mutex, shim::to_ns(*deadline) - offset);
}

}  // extern "C"
