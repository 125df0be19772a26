// timerfd on a sim clock (docs/timeshim.md, "What it intercepts"): the fd
// is an eventfd, the timer a slot the controller sees (its deadline is one
// the group can wake at), and the process's helper thread writes the
// expirations to the eventfd when the controller wakes it at the deadline.
#include "timers.hpp"

#include <fcntl.h>
#include <sys/eventfd.h>
#include <sys/timerfd.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>

#include "runtime.hpp"

namespace shim = ubersim::timeshim::shim;
using ubersim::timeshim::kNoDeadline;
using ubersim::timeshim::ShimCall;
using ubersim::timeshim::ThreadSlot;
using ubersim::timeshim::ThreadState;

namespace {

using ubersim::timeshim::shim::kMaxFd;
std::atomic<ThreadSlot*> timers[kMaxFd];
// The clock's offset from sim time, by fd (what an absolute time means).
std::atomic<std::int64_t> fd_clock_offsets[kMaxFd];

ThreadSlot* timer_of(int fd) {
  if (fd < 0 || fd >= kMaxFd) return nullptr;
  return timers[fd].load();
}

// A re-armed timer starts counting anew: empty the eventfd.
void drain(int fd) {
  const int flags = ::fcntl(fd, F_GETFL);
  ::fcntl(fd, F_SETFL, flags | O_NONBLOCK);
  std::uint64_t count = 0;
  if (::read(fd, &count, sizeof(count)) < 0) {
    // Nothing was there.
  }
  ::fcntl(fd, F_SETFL, flags);
}

}  // namespace

namespace ubersim::timeshim::shim {

itimerspec timer_setting(const ThreadSlot& slot) {
  itimerspec value{};
  const std::int64_t deadline = slot.deadline_ns.load();
  if (deadline != kNoDeadline) {
    value.it_value = to_timespec(std::max<std::int64_t>(1, deadline - view_now()));
  }
  value.it_interval = to_timespec(slot.interval_ns.load());
  return value;
}

void forget_timer(int fd) {
  if (fd < 0 || fd >= kMaxFd) return;
  ThreadSlot* slot = timers[fd].exchange(nullptr);
  if (slot != nullptr) release_other_slot(*slot);
}

}  // namespace ubersim::timeshim::shim

extern "C" {

__attribute__((visibility("default"))) int timerfd_create(clockid_t clock, int flags) noexcept {
  std::int64_t offset = 0;
  if (shim::segment() == nullptr || !shim::sim_clock(clock, &offset)) {
    static const auto real = shim::next_symbol<int (*)(clockid_t, int)>("timerfd_create");
    return real(clock, flags);
  }
  // TFD_NONBLOCK and TFD_CLOEXEC are EFD_NONBLOCK and EFD_CLOEXEC.
  const int fd = ::eventfd(0, flags & (EFD_NONBLOCK | EFD_CLOEXEC));
  if (fd < 0) return -1;
  ThreadSlot* slot = fd < kMaxFd ? shim::claim_other_slot() : nullptr;
  if (slot == nullptr) {
    ::close(fd);
    errno = EMFILE;
    return -1;
  }
  slot->timer_fd.store(fd);
  slot->timer_kind.store(static_cast<std::uint32_t>(ubersim::timeshim::TimerKind::Fd));
  slot->interval_ns.store(0);
  slot->state.store(static_cast<std::uint32_t>(ThreadState::Timer));
  fd_clock_offsets[fd].store(offset);
  timers[fd].store(slot);
  shim::ensure_helper();
  return fd;
}

__attribute__((visibility("default"))) int timerfd_settime(int fd, int flags,
                                                           const itimerspec* value,
                                                           itimerspec* old_value) noexcept {
  ThreadSlot* slot = timer_of(fd);
  if (slot == nullptr) {
    static const auto real =
        shim::next_symbol<int (*)(int, int, const itimerspec*, itimerspec*)>("timerfd_settime");
    return real(fd, flags, value, old_value);
  }
  if (value->it_value.tv_nsec < 0 || value->it_value.tv_nsec >= shim::kNsPerSecond ||
      value->it_interval.tv_nsec < 0 || value->it_interval.tv_nsec >= shim::kNsPerSecond) {
    errno = EINVAL;
    return -1;
  }
  if (old_value != nullptr) *old_value = shim::timer_setting(*slot);
  const std::int64_t start = shim::to_ns(value->it_value);
  std::int64_t deadline = kNoDeadline;
  if (start != 0) {
    deadline = (flags & TFD_TIMER_ABSTIME) != 0 ? start - fd_clock_offsets[fd].load()
                                                : shim::deadline_after(shim::view_now(), start);
  }
  drain(fd);
  slot->interval_ns.store(shim::to_ns(value->it_interval));
  slot->deadline_ns.store(deadline);
  shim::charge_call();
  shim::notify();
  return 0;
}

__attribute__((visibility("default"))) int timerfd_gettime(int fd, itimerspec* value) noexcept {
  ThreadSlot* slot = timer_of(fd);
  if (slot == nullptr) {
    static const auto real = shim::next_symbol<int (*)(int, itimerspec*)>("timerfd_gettime");
    return real(fd, value);
  }
  *value = shim::timer_setting(*slot);
  return 0;
}

}  // extern "C"
