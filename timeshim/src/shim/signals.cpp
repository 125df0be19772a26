// Signal waits and signal timers on sim time (docs/timeshim.md, "What it
// intercepts"): sigtimedwait's timeout is a sim deadline; alarm and
// setitimer(ITIMER_REAL) are a POSIX timer of the shim's (posix_timers.cpp)
// that sends SIGALRM to the process.
#include <signal.h>
#include <sys/time.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>

#include "runtime.hpp"
#include "timers.hpp"

namespace shim = ubersim::timeshim::shim;
using ubersim::timeshim::ShimCall;
using ubersim::timeshim::ThreadState;

namespace {

using SigtimedwaitFn = int (*)(const sigset_t*, siginfo_t*, const timespec*);

int real_sigtimedwait(const sigset_t* set, siginfo_t* info, const timespec* timeout) {
  static const auto next = shim::next_symbol<SigtimedwaitFn>("sigtimedwait");
  return next(set, info, timeout);
}

// Waits for a signal of `set` until the sim deadline. The controller's wake
// signal is added to the set: at the deadline it ends the kernel's wait
// (taken by it, not by a handler).
int sigtimedwait_until(const sigset_t* set, siginfo_t* info, std::int64_t deadline) {
  constexpr timespec kNoWait{0, 0};
  const int ready = real_sigtimedwait(set, info, &kNoWait);
  if (ready > 0 || deadline <= shim::view_now()) {
    shim::charge_call();
    return ready;
  }
  const int wake = shim::segment()->wake_signal;
  sigset_t with_wake = *set;
  sigaddset(&with_wake, wake);
  shim::WaitScope scope(deadline, ShimCall::SigTimedwait, ThreadState::WaitingFd, nullptr);
  for (;;) {
    if (scope.deadline_passed()) {
      scope.set_timed_out();
      errno = EAGAIN;
      return -1;
    }
    const int got = real_sigtimedwait(&with_wake, info, &shim::kLivenessCheck);
    if (got == wake) continue;
    if (got > 0) return got;
    if (errno == EAGAIN) {
      shim::exit_if_controller_gone();
      continue;
    }
    return -1;  // EINTR: a handler of the program's ran
  }
}

// The process's ITIMER_REAL (alarm, setitimer): created at first use; a
// forked child has none (pid differs).
std::atomic<timer_t> real_timer{nullptr};
std::atomic<pid_t> real_timer_pid{0};

timer_t process_real_timer() {
  if (real_timer_pid.load() != ::getpid()) {
    sigevent event{};
    event.sigev_notify = SIGEV_SIGNAL;
    event.sigev_signo = SIGALRM;
    real_timer.store(shim::create_sim_timer(CLOCK_MONOTONIC, &event));
    real_timer_pid.store(::getpid());
  }
  return real_timer.load();
}

itimerspec to_itimerspec(const itimerval& value) {
  itimerspec result{};
  result.it_value = {value.it_value.tv_sec, value.it_value.tv_usec * 1000};
  result.it_interval = {value.it_interval.tv_sec, value.it_interval.tv_usec * 1000};
  return result;
}

itimerval to_itimerval(const itimerspec& value) {
  itimerval result{};
  // Round up, as the kernel does: a timer that is armed never reads 0.
  const auto micros = [](const timespec& t) {
    timeval v{t.tv_sec, (t.tv_nsec + 999) / 1000};
    if (v.tv_usec >= 1000000) {
      v.tv_sec += 1;
      v.tv_usec -= 1000000;
    }
    return v;
  };
  result.it_value = micros(value.it_value);
  result.it_interval = micros(value.it_interval);
  return result;
}

}  // namespace

extern "C" {

__attribute__((visibility("default"))) int sigtimedwait(const sigset_t* set, siginfo_t* info,
                                                        const timespec* timeout) {
  if (shim::segment() == nullptr) return real_sigtimedwait(set, info, timeout);
  // No timeout: sigwaitinfo (which hands the token over in deterministic mode).
  if (timeout == nullptr) return sigwaitinfo(set, info);
  if (timeout->tv_nsec < 0 || timeout->tv_nsec >= shim::kNsPerSecond) {
    errno = EINVAL;
    return -1;
  }
  siginfo_t ignored{};
  return sigtimedwait_until(set, info != nullptr ? info : &ignored,
                            shim::deadline_after(shim::view_now(), shim::to_ns(*timeout)));
}

__attribute__((visibility("default"))) int setitimer(int which, const itimerval* value,
                                                     itimerval* old_value) noexcept {
  if (shim::segment() == nullptr || which != ITIMER_REAL) {
    static const auto real =
        shim::next_symbol<int (*)(int, const itimerval*, itimerval*)>("setitimer");
    return real(which, value, old_value);
  }
  if (value->it_value.tv_usec < 0 || value->it_value.tv_usec >= 1000000 ||
      value->it_interval.tv_usec < 0 || value->it_interval.tv_usec >= 1000000) {
    errno = EINVAL;
    return -1;
  }
  const timer_t timer = process_real_timer();
  if (timer == nullptr) {
    errno = EAGAIN;
    return -1;
  }
  const itimerspec wanted = to_itimerspec(*value);
  itimerspec old{};
  if (shim::set_sim_timer(timer, 0, &wanted, &old) != 0) return -1;
  if (old_value != nullptr) *old_value = to_itimerval(old);
  return 0;
}

__attribute__((visibility("default"))) int getitimer(int which, itimerval* value) noexcept {
  if (shim::segment() == nullptr || which != ITIMER_REAL) {
    static const auto real = shim::next_symbol<int (*)(int, itimerval*)>("getitimer");
    return real(which, value);
  }
  const timer_t timer = process_real_timer();
  itimerspec current{};
  if (timer == nullptr || shim::get_sim_timer(timer, &current) != 0) {
    *value = itimerval{};
    return 0;
  }
  *value = to_itimerval(current);
  return 0;
}

__attribute__((visibility("default"))) unsigned int alarm(unsigned int seconds) noexcept {
  if (shim::segment() == nullptr) {
    static const auto real = shim::next_symbol<unsigned int (*)(unsigned int)>("alarm");
    return real(seconds);
  }
  itimerval wanted{};
  wanted.it_value.tv_sec = seconds;
  itimerval old{};
  if (setitimer(ITIMER_REAL, &wanted, &old) != 0) return 0;
  // What was left, rounded to the nearest second but never 0 while armed.
  unsigned int left = static_cast<unsigned int>(old.it_value.tv_sec);
  if (old.it_value.tv_usec >= 500000 || (left == 0 && old.it_value.tv_usec > 0)) ++left;
  return left;
}

}  // extern "C"
