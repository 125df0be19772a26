// POSIX timers on a sim clock (timer_create and its kin; docs/timeshim.md,
// "What it intercepts"): a timer is a slot the controller sees, like a
// timerfd's; when sim time reaches it, the process's helper thread sends its
// signal (SIGEV_SIGNAL, SIGEV_THREAD_ID) or starts a thread that calls its
// function (SIGEV_THREAD). The timer ids are the shim's own (a tag and the
// slot), never the kernel's.
#include <pthread.h>
#include <signal.h>
#include <sys/syscall.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <memory>

#include "runtime.hpp"
#include "timers.hpp"

namespace shim = ubersim::timeshim::shim;
using ubersim::timeshim::kMaxThreads;
using ubersim::timeshim::kNoDeadline;
using ubersim::timeshim::ThreadSlot;
using ubersim::timeshim::ThreadState;
using ubersim::timeshim::TimerKind;

namespace {

constexpr std::uint64_t kTag = 0x7ee5000000000000ULL;
constexpr std::uint64_t kTagMask = 0xffff000000000000ULL;
// The clock's offset from sim time, by slot (what an absolute time means).
std::atomic<std::int64_t> slot_clock_offsets[kMaxThreads];

std::size_t index_of(const ThreadSlot& slot) {
  return static_cast<std::size_t>(&slot - shim::segment()->threads);
}

// The shim's timer of this process with this id, or nullptr (a kernel timer).
ThreadSlot* sim_timer(timer_t id) {
  const auto value = reinterpret_cast<std::uint64_t>(id);
  if ((value & kTagMask) != kTag || shim::segment() == nullptr) return nullptr;
  const std::uint64_t index = value & ~kTagMask;
  if (index >= static_cast<std::uint64_t>(kMaxThreads)) return nullptr;
  ThreadSlot& slot = shim::segment()->threads[index];
  if (slot.claim.load() == 0 || slot.pid.load() != ::getpid() ||
      slot.state.load() != static_cast<std::uint32_t>(ThreadState::Timer) ||
      slot.timer_kind.load() != static_cast<std::uint32_t>(TimerKind::Posix)) {
    return nullptr;
  }
  return &slot;
}

struct ThreadCall {
  void (*function)(sigval);
  sigval value;
};

void* call_timer_function(void* raw) {
  const std::unique_ptr<ThreadCall> call(static_cast<ThreadCall*>(raw));
  call->function(call->value);
  return nullptr;
}

sigval value_of(const ThreadSlot& slot) {
  sigval value{};
  // The value the program gave, kept as an integer in the shared slot.
  value.sival_ptr = reinterpret_cast<void*>(  // NOLINT(performance-no-int-to-ptr)
      slot.timer_value.load());
  return value;
}

}  // namespace

namespace ubersim::timeshim::shim {

timer_t create_sim_timer(clockid_t clock, const sigevent* event) {
  std::int64_t offset = 0;
  sim_clock(clock, &offset);
  ThreadSlot* slot = claim_other_slot();
  if (slot == nullptr) return nullptr;
  // An id, not an address: the tag and the slot's index.
  const auto id = reinterpret_cast<timer_t>(  // NOLINT(performance-no-int-to-ptr)
      kTag | index_of(*slot));
  slot->timer_kind.store(static_cast<std::uint32_t>(TimerKind::Posix));
  slot->timer_notify.store(event != nullptr ? event->sigev_notify : SIGEV_SIGNAL);
  slot->timer_signal.store(event != nullptr ? event->sigev_signo : SIGALRM);
  // Without a sigevent, the signal's value is the timer's id.
  slot->timer_value.store(reinterpret_cast<std::uint64_t>(
      event != nullptr ? event->sigev_value.sival_ptr : static_cast<void*>(id)));
  slot->timer_function.store(
      event != nullptr ? reinterpret_cast<std::uint64_t>(event->sigev_notify_function) : 0);
  slot->timer_tid.store(event != nullptr ? event->_sigev_un._tid : 0);
  slot->timer_overrun.store(0);
  slot->interval_ns.store(0);
  slot_clock_offsets[index_of(*slot)].store(offset);
  slot->state.store(static_cast<std::uint32_t>(ThreadState::Timer));
  ensure_helper();
  return id;
}

int set_sim_timer(timer_t id, int flags, const itimerspec* value, itimerspec* old_value) {
  ThreadSlot* slot = sim_timer(id);
  if (slot == nullptr || value->it_value.tv_nsec < 0 || value->it_value.tv_nsec >= kNsPerSecond ||
      value->it_interval.tv_nsec < 0 || value->it_interval.tv_nsec >= kNsPerSecond) {
    errno = EINVAL;
    return -1;
  }
  if (old_value != nullptr) *old_value = shim::timer_setting(*slot);
  const std::int64_t start = to_ns(value->it_value);
  std::int64_t deadline = kNoDeadline;
  if (start != 0) {
    deadline = (flags & TIMER_ABSTIME) != 0 ? start - slot_clock_offsets[index_of(*slot)].load()
                                            : deadline_after(view_now(), start);
  }
  slot->interval_ns.store(to_ns(value->it_interval));
  slot->timer_overrun.store(0);
  slot->deadline_ns.store(deadline);
  charge_call();
  notify();
  return 0;
}

int get_sim_timer(timer_t id, itimerspec* value) {
  ThreadSlot* slot = sim_timer(id);
  if (slot == nullptr) {
    errno = EINVAL;
    return -1;
  }
  *value = shim::timer_setting(*slot);
  return 0;
}

void fire_posix_timer(ThreadSlot& slot, std::uint64_t expirations) {
  slot.timer_overrun.store(
      static_cast<std::int32_t>(std::min<std::uint64_t>(expirations - 1, 1U << 30)));
  const int signal_number = slot.timer_signal.load();
  switch (slot.timer_notify.load()) {
    case SIGEV_SIGNAL:
      ::sigqueue(::getpid(), signal_number, value_of(slot));
      break;
    case SIGEV_THREAD_ID: {
      siginfo_t info{};
      info.si_signo = signal_number;
      info.si_code = SI_QUEUE;
      info.si_pid = ::getpid();
      info.si_uid = ::getuid();
      info.si_value = value_of(slot);
      ::syscall(SYS_rt_tgsigqueueinfo, ::getpid(), slot.timer_tid.load(), signal_number, &info);
      shim::segment()->signals_sent.fetch_add(1);  // as sigqueue above counts it (det_sync.cpp)
      break;
    }
    case SIGEV_THREAD: {
      // A new thread per expiry, as glibc does (the sigevent's thread
      // attributes are not kept: default ones, detached).
      // The function's address in this process, kept as an integer in the slot.
      auto call = std::make_unique<ThreadCall>(
          ThreadCall{reinterpret_cast<void (*)(sigval)>(  // NOLINT(performance-no-int-to-ptr)
                         slot.timer_function.load()),
                     value_of(slot)});
      pthread_attr_t attributes;
      pthread_attr_init(&attributes);
      pthread_attr_setdetachstate(&attributes, PTHREAD_CREATE_DETACHED);
      pthread_t thread;
      if (pthread_create(&thread, &attributes, call_timer_function, call.get()) == 0) {
        static_cast<void>(call.release());  // the thread owns it now
      }
      pthread_attr_destroy(&attributes);
      break;
    }
    default:  // SIGEV_NONE: only timer_gettime sees it
      break;
  }
}

}  // namespace ubersim::timeshim::shim

extern "C" {

__attribute__((visibility("default"))) int timer_create(clockid_t clock, sigevent* event,
                                                        timer_t* id) noexcept {
  std::int64_t offset = 0;
  if (shim::segment() == nullptr || !shim::sim_clock(clock, &offset)) {
    static const auto real =
        shim::next_symbol<int (*)(clockid_t, sigevent*, timer_t*)>("timer_create");
    return real(clock, event, id);
  }
  if (event != nullptr && event->sigev_notify != SIGEV_SIGNAL &&
      event->sigev_notify != SIGEV_NONE && event->sigev_notify != SIGEV_THREAD &&
      event->sigev_notify != SIGEV_THREAD_ID) {
    errno = EINVAL;
    return -1;
  }
  const timer_t created = shim::create_sim_timer(clock, event);
  if (created == nullptr) {
    errno = EAGAIN;
    return -1;
  }
  *id = created;
  return 0;
}

__attribute__((visibility("default"))) int timer_settime(timer_t id, int flags,
                                                         const itimerspec* value,
                                                         itimerspec* old_value) noexcept {
  if (sim_timer(id) == nullptr) {
    static const auto real =
        shim::next_symbol<int (*)(timer_t, int, const itimerspec*, itimerspec*)>("timer_settime");
    return real(id, flags, value, old_value);
  }
  return shim::set_sim_timer(id, flags, value, old_value);
}

__attribute__((visibility("default"))) int timer_gettime(timer_t id, itimerspec* value) noexcept {
  if (sim_timer(id) == nullptr) {
    static const auto real = shim::next_symbol<int (*)(timer_t, itimerspec*)>("timer_gettime");
    return real(id, value);
  }
  return shim::get_sim_timer(id, value);
}

__attribute__((visibility("default"))) int timer_getoverrun(timer_t id) noexcept {
  ThreadSlot* slot = sim_timer(id);
  if (slot == nullptr) {
    static const auto real = shim::next_symbol<int (*)(timer_t)>("timer_getoverrun");
    return real(id);
  }
  return slot->timer_overrun.load();
}

__attribute__((visibility("default"))) int timer_delete(timer_t id) noexcept {
  ThreadSlot* slot = sim_timer(id);
  if (slot == nullptr) {
    static const auto real = shim::next_symbol<int (*)(timer_t)>("timer_delete");
    return real(id);
  }
  shim::release_other_slot(*slot);
  return 0;
}

}  // extern "C"
