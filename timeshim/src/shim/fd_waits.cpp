// Waits for fd readiness with a timeout (docs/timeshim.md, "What it
// intercepts"): the timeout becomes a sim-time deadline; the call waits, with
// no wall-time limit, for readiness or for the controller's wake signal once
// sim time passed the deadline.
#include "fd_waits.hpp"

#include <poll.h>
#include <sys/epoll.h>
#include <sys/select.h>

#include <cstring>
#include <vector>

#include "runtime.hpp"

namespace shim = ubersim::timeshim::shim;
using ubersim::timeshim::kNoDeadline;
using ubersim::timeshim::ShimCall;
using ubersim::timeshim::ThreadState;

namespace {

using PpollFn = int (*)(pollfd*, nfds_t, const timespec*, const sigset_t*);
using PselectFn = int (*)(int, fd_set*, fd_set*, fd_set*, const timespec*, const sigset_t*);
using EpollPwaitFn = int (*)(int, epoll_event*, int, int, const sigset_t*);

int real_ppoll(pollfd* fds, nfds_t count, const timespec* timeout, const sigset_t* mask) {
  static const auto real = shim::next_symbol<PpollFn>("ppoll");
  return real(fds, count, timeout, mask);
}
int real_pselect(int count, fd_set* readable, fd_set* writable, fd_set* failed,
                 const timespec* timeout, const sigset_t* mask) {
  static const auto real = shim::next_symbol<PselectFn>("pselect");
  return real(count, readable, writable, failed, timeout, mask);
}
int real_epoll_pwait(int epoll, epoll_event* events, int count, int timeout_ms,
                     const sigset_t* mask) {
  static const auto real = shim::next_symbol<EpollPwaitFn>("epoll_pwait");
  return real(epoll, events, count, timeout_ms, mask);
}

constexpr timespec kZero{0, 0};

// Sim deadline of a timeout in ms (negative: none).
std::int64_t deadline_ms(int timeout_ms) {
  if (timeout_ms < 0) return kNoDeadline;
  return shim::view_now() + static_cast<std::int64_t>(timeout_ms) * 1000000;
}
std::int64_t deadline_ts(const timespec* timeout) {
  if (timeout == nullptr) return kNoDeadline;
  return shim::deadline_after(shim::view_now(), shim::to_ns(*timeout));
}

// The three fd sets of a select, kept to start each try from the caller's.
class FdSets {
 public:
  FdSets(int count, fd_set* readable, fd_set* writable, fd_set* failed)
      : bytes_(static_cast<std::size_t>((count + 63) / 64) * 8), sets_{readable, writable, failed} {
    for (int i = 0; i < 3; ++i) {
      if (sets_[i] != nullptr) {
        const auto* raw = reinterpret_cast<const unsigned char*>(sets_[i]);
        saved_[i].assign(raw, raw + bytes_);
      }
    }
  }
  void restore() {
    for (int i = 0; i < 3; ++i) {
      if (sets_[i] != nullptr) std::memcpy(sets_[i], saved_[i].data(), bytes_);
    }
  }
  void clear() {
    for (auto* set : sets_) {
      if (set != nullptr) std::memset(set, 0, bytes_);
    }
  }

 private:
  std::size_t bytes_;
  fd_set* sets_[3];
  std::vector<unsigned char> saved_[3];
};

int select_until(int count, fd_set* readable, fd_set* writable, fd_set* failed,
                 std::int64_t deadline, const sigset_t* app_mask, ShimCall call) {
  FdSets sets(count, readable, writable, failed);
  const int ready = real_pselect(count, readable, writable, failed, &kZero, app_mask);
  if (ready != 0 || deadline <= shim::view_now()) {
    shim::charge_call();
    return ready;
  }
  bool timed_out = false;
  const int result = shim::wait_until(
      deadline, call, ThreadState::WaitingFd, app_mask, &timed_out, [&](const sigset_t* mask) {
        sets.restore();
        return real_pselect(count, readable, writable, failed, &shim::kLivenessCheck, mask);
      });
  if (timed_out) sets.clear();
  return result;
}

int epoll_until(int epoll, epoll_event* events, int count, std::int64_t deadline,
                const sigset_t* app_mask, ShimCall call) {
  const int ready = real_epoll_pwait(epoll, events, count, 0, app_mask);
  if (ready != 0 || deadline <= shim::view_now()) {
    shim::charge_call();
    return ready;
  }
  bool timed_out = false;
  return shim::wait_until(
      deadline, call, ThreadState::WaitingFd, app_mask, &timed_out, [=](const sigset_t* mask) {
        return real_epoll_pwait(epoll, events, count, shim::kLivenessCheckMs, mask);
      });
}

}  // namespace

namespace ubersim::timeshim::shim {

int poll_until(pollfd* fds, nfds_t count, std::int64_t deadline, const sigset_t* app_mask,
               ShimCall call) {
  // Ready now (or an error): no wait, and no state change to tell anyone.
  const int ready = real_ppoll(fds, count, &kZero, app_mask);
  if (ready != 0 || deadline <= shim::view_now()) {
    shim::charge_call();
    return ready;
  }
  bool timed_out = false;
  const int result = shim::wait_until(deadline, call, ThreadState::WaitingFd, app_mask, &timed_out,
                                      [fds, count](const sigset_t* mask) {
                                        return real_ppoll(fds, count, &shim::kLivenessCheck, mask);
                                      });
  if (timed_out) {
    for (nfds_t i = 0; i < count; ++i) fds[i].revents = 0;
  }
  return result;
}

}  // namespace ubersim::timeshim::shim

using shim::poll_until;

extern "C" {

__attribute__((visibility("default"))) int poll(pollfd* fds, nfds_t count, int timeout_ms) {
  if (shim::segment() == nullptr) {
    const timespec timeout = shim::to_timespec(static_cast<std::int64_t>(timeout_ms) * 1000000);
    return real_ppoll(fds, count, timeout_ms < 0 ? nullptr : &timeout, nullptr);
  }
  return poll_until(fds, count, deadline_ms(timeout_ms), nullptr, ShimCall::Poll);
}

__attribute__((visibility("default"))) int ppoll(pollfd* fds, nfds_t count, const timespec* timeout,
                                                 const sigset_t* mask) {
  if (shim::segment() == nullptr) return real_ppoll(fds, count, timeout, mask);
  return poll_until(fds, count, deadline_ts(timeout), mask, ShimCall::Ppoll);
}

// The _FORTIFY_SOURCE entry points, which glibc would route past the shim
// (glibc's names, so reserved identifiers).
// NOLINTNEXTLINE(bugprone-reserved-identifier)
__attribute__((visibility("default"))) int __poll_chk(pollfd* fds, nfds_t count, int timeout_ms,
                                                      unsigned long /*fds_length*/) {
  return poll(fds, count, timeout_ms);
}
// NOLINTNEXTLINE(bugprone-reserved-identifier)
__attribute__((visibility("default"))) int __ppoll_chk(pollfd* fds, nfds_t count,
                                                       const timespec* timeout,
                                                       const sigset_t* mask,
                                                       unsigned long /*fds_length*/) {
  return ppoll(fds, count, timeout, mask);
}

__attribute__((visibility("default"))) int select(int count, fd_set* readable, fd_set* writable,
                                                  fd_set* failed, timeval* timeout) {
  if (shim::segment() == nullptr) {
    static const auto real =
        shim::next_symbol<int (*)(int, fd_set*, fd_set*, fd_set*, timeval*)>("select");
    return real(count, readable, writable, failed, timeout);
  }
  std::int64_t deadline = kNoDeadline;
  if (timeout != nullptr) {
    deadline = shim::deadline_after(
        shim::view_now(), static_cast<std::int64_t>(timeout->tv_sec) * shim::kNsPerSecond +
                              static_cast<std::int64_t>(timeout->tv_usec) * 1000);
  }
  const int result =
      select_until(count, readable, writable, failed, deadline, nullptr, ShimCall::Select);
  if (timeout != nullptr) {
    // Linux's select says how much of the timeout was left.
    const std::int64_t left = std::max<std::int64_t>(0, deadline - shim::view_now());
    timeout->tv_sec = static_cast<time_t>(left / shim::kNsPerSecond);
    timeout->tv_usec = static_cast<suseconds_t>((left % shim::kNsPerSecond) / 1000);
  }
  return result;
}

__attribute__((visibility("default"))) int pselect(int count, fd_set* readable, fd_set* writable,
                                                   fd_set* failed, const timespec* timeout,
                                                   const sigset_t* mask) {
  if (shim::segment() == nullptr) {
    return real_pselect(count, readable, writable, failed, timeout, mask);
  }
  return select_until(count, readable, writable, failed, deadline_ts(timeout), mask,
                      ShimCall::Pselect);
}

__attribute__((visibility("default"))) int epoll_wait(int epoll, epoll_event* events, int count,
                                                      int timeout_ms) {
  if (shim::segment() == nullptr)
    return real_epoll_pwait(epoll, events, count, timeout_ms, nullptr);
  return epoll_until(epoll, events, count, deadline_ms(timeout_ms), nullptr, ShimCall::EpollWait);
}

__attribute__((visibility("default"))) int epoll_pwait2(int epoll, epoll_event* events, int count,
                                                        const timespec* timeout,
                                                        const sigset_t* mask) {
  if (shim::segment() == nullptr) {
    static const auto real =
        shim::next_symbol<int (*)(int, epoll_event*, int, const timespec*, const sigset_t*)>(
            "epoll_pwait2");
    return real(epoll, events, count, timeout, mask);
  }
  return epoll_until(epoll, events, count, deadline_ts(timeout), mask, ShimCall::EpollPwait2);
}

__attribute__((visibility("default"))) int epoll_pwait(int epoll, epoll_event* events, int count,
                                                       int timeout_ms, const sigset_t* mask) {
  if (shim::segment() == nullptr) return real_epoll_pwait(epoll, events, count, timeout_ms, mask);
  return epoll_until(epoll, events, count, deadline_ms(timeout_ms), mask, ShimCall::EpollPwait);
}

}  // extern "C"
