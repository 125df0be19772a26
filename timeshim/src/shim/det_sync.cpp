// Deterministic mode (docs/timeshim.md, "Deterministic mode"): the group's
// threads run one at a time, each until it blocks. A thread that would block
// in the kernel while it holds the run token would stop the whole group, so
// what threads block in is either done in the shim (mutexes, condition
// variables, semaphores: the token holder's unlock, signal or post makes the
// waiters want the token, in a fixed order) or hands the token over for the
// time of the call (joins, waits for children, blocking reads, signal waits).
// Outside deterministic mode every call here goes straight to libc.
#include "det_sync.hpp"

#include <fcntl.h>
#include <poll.h>
#include <pthread.h>
#include <sched.h>
#include <semaphore.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <memory>

#include "fd_waits.hpp"
#include "runtime.hpp"

namespace shim = ubersim::timeshim::shim;
using ubersim::timeshim::DetObject;
using ubersim::timeshim::Header;
using ubersim::timeshim::kNoDeadline;
using ubersim::timeshim::ShimCall;
using ubersim::timeshim::ThreadSlot;
using ubersim::timeshim::ThreadState;

namespace {

int real_mutex_trylock(pthread_mutex_t* mutex) {
  static const auto next = shim::next_symbol<int (*)(pthread_mutex_t*)>("pthread_mutex_trylock");
  return next(mutex);
}
int real_mutex_lock(pthread_mutex_t* mutex) {
  static const auto next = shim::next_symbol<int (*)(pthread_mutex_t*)>("pthread_mutex_lock");
  return next(mutex);
}
int real_mutex_unlock(pthread_mutex_t* mutex) {
  static const auto next = shim::next_symbol<int (*)(pthread_mutex_t*)>("pthread_mutex_unlock");
  return next(mutex);
}
int real_sem_trywait(sem_t* semaphore) {
  static const auto next = shim::next_symbol<int (*)(sem_t*)>("sem_trywait");
  return next(semaphore);
}

// glibc's semaphore: {uint64 value and waiters, int private, int pad};
// `private` is 0 for a process-private one and FUTEX_PRIVATE_FLAG (128,
// glibc's LLL_SHARED) for a process-shared one (sem_open, or sem_init with
// pshared), which other processes map at other addresses.
bool is_shared(const sem_t* semaphore) {
  int futex_private = 0;
  static_assert(sizeof(sem_t) >= 12);
  __builtin_memcpy(&futex_private, reinterpret_cast<const char*>(semaphore) + 8, sizeof(int));
  return futex_private != 0;
}

// This thread made another want the token since it last yielded: at its
// next unlock or post it lets that one run first.
__attribute__((tls_model("initial-exec"))) thread_local bool woke_someone = false;

// Makes `slot` (DetBlocked) want the token: a peer ended its wait. Its place
// in the queue is given now, by the token holder, ahead of whoever asks
// later (the waker, when it yields).
void make_ready(ThreadSlot& slot, Header& segment) {
  slot.det_signaled.store(1);
  slot.ready_seq.store(next_ready_place(segment));
  auto blocked = static_cast<std::uint32_t>(ThreadState::DetBlocked);
  if (slot.state.compare_exchange_strong(blocked,
                                         static_cast<std::uint32_t>(ThreadState::WantToken))) {
    woke_someone = true;
    shim::notify();
  }
}

// After an unlock or post that woke a thread: the waker lets it run first,
// as it would have on another core (a thread that releases and retakes a
// lock in a loop, CPython's GIL among them, would otherwise keep it for ever).
void yield_to_woken() {
  if (!woke_someone || !shim::holds_token()) return;
  woke_someone = false;
  const int saved = errno;
  ThreadSlot& slot = shim::own_slot();
  shim::end_turn(slot, ThreadState::WantToken, ShimCall::BlockingCall, kNoDeadline);
  shim::acquire_token(slot, ShimCall::BlockingCall);
  shim::set_state(slot, ThreadState::Running, ShimCall::None, kNoDeadline);
  errno = saved;
}

// getpid(), not the slot's pid: a vfork or posix_spawn child runs no fork
// handler and still has its parent's slot. Asked only when a waiter on the
// same address is found: glibc's getpid is a system call, and CPython's GIL
// unlocks often.
class OwnPid {
 public:
  pid_t get() {
    if (pid_ == 0) pid_ = ::getpid();
    return pid_;
  }

 private:
  pid_t pid_ = 0;
};

bool waits_for(const ThreadSlot& slot, DetObject object, const void* address, bool shared,
               OwnPid& pid) {
  if (slot.claim.load() == 0 ||
      slot.state.load() != static_cast<std::uint32_t>(ThreadState::DetBlocked) ||
      slot.det_object.load() != static_cast<std::uint32_t>(object)) {
    return false;
  }
  if (shared && slot.det_shared.load() != 0) return true;
  return slot.cond_addr.load() == reinterpret_cast<std::uint64_t>(address) &&
         slot.pid.load() == pid.get();
}

}  // namespace

namespace ubersim::timeshim::shim {

bool det_block(DetObject object, const void* address, bool shared, std::int64_t deadline,
               ShimCall call) {
  Header& segment = *shim::segment();
  ThreadSlot& slot = own_slot();
  const std::int64_t view_at_start = view_now();
  slot.cond_addr.store(reinterpret_cast<std::uint64_t>(address));
  slot.det_object.store(static_cast<std::uint32_t>(object));
  slot.det_shared.store(shared ? 1 : 0);
  slot.det_signaled.store(0);
  slot.det_wait_seq.store(segment.det_wait_counter.fetch_add(1));
  segment.det_blocked.fetch_add(1);
  woke_someone = false;  // those it woke run before it anyway
  end_turn(slot, ThreadState::DetBlocked, call, deadline);
  wait_for_turn(slot);
  segment.det_blocked.fetch_sub(1);
  const bool signaled = slot.det_signaled.load() != 0;
  slot.det_object.store(static_cast<std::uint32_t>(DetObject::None));
  set_state(slot, ThreadState::Running, ShimCall::None, kNoDeadline);
  after_block(view_at_start, signaled ? 0 : deadline, call);
  return signaled;
}

void det_wake(DetObject object, const void* address, bool shared, bool only_first) {
  Header& segment = *shim::segment();
  if (segment.det_blocked.load() == 0) return;
  OwnPid pid;
  // Longest waiter first: their places in the queue follow the order they
  // began to wait in (given out in turns), not the slots' order, which is
  // the order new threads happened to claim them in.
  for (;;) {
    ThreadSlot* first = nullptr;
    for (auto& slot : used_slots(segment)) {
      if (!waits_for(slot, object, address, shared, pid)) continue;
      if (first == nullptr || slot.det_wait_seq.load() < first->det_wait_seq.load()) first = &slot;
    }
    if (first == nullptr) return;
    make_ready(*first, segment);  // no longer DetBlocked: not found again
    if (only_first) return;
  }
}

int det_mutex_lock(pthread_mutex_t* mutex, std::int64_t deadline) {
  for (;;) {
    const int result = real_mutex_trylock(mutex);
    if (result != EBUSY) return result;
    // Its owner asks again: an error-checking mutex says EDEADLK, a plain
    // one deadlocks, as without the shim.
    if (mutex->__data.__owner == static_cast<int>(::syscall(SYS_gettid)))
      return real_mutex_lock(mutex);
    if (deadline <= view_now()) return ETIMEDOUT;
    if (!det_block(DetObject::Mutex, mutex, false, deadline, ShimCall::MutexLock) &&
        deadline != kNoDeadline) {
      return real_mutex_trylock(mutex) == 0 ? 0 : ETIMEDOUT;
    }
  }
}

int det_cond_wait(pthread_cond_t* cond, pthread_mutex_t* mutex, std::int64_t deadline) {
  if (deadline <= view_now()) {
    charge_call();
    return ETIMEDOUT;
  }
  // Nobody else runs while this thread holds the token: no signal can come
  // between the unlock and the block.
  const int unlocked = real_mutex_unlock(mutex);
  if (unlocked != 0) return unlocked;
  det_wake(DetObject::Mutex, mutex, false, false);
  const bool signaled =
      det_block(DetObject::Cond, cond, false, deadline,
                deadline == kNoDeadline ? ShimCall::CondWait : ShimCall::CondTimedwait);
  det_mutex_lock(mutex, kNoDeadline);
  return signaled ? 0 : ETIMEDOUT;
}

int det_sem_wait(sem_t* semaphore, std::int64_t deadline) {
  for (;;) {
    if (real_sem_trywait(semaphore) == 0) return 0;
    if (errno != EAGAIN) return -1;
    if (deadline <= view_now()) {
      charge_call();
      errno = ETIMEDOUT;
      return -1;
    }
    const ShimCall call = deadline == kNoDeadline ? ShimCall::SemWait : ShimCall::SemTimedwait;
    if (!det_block(DetObject::Sem, semaphore, is_shared(semaphore), deadline, call)) {
      if (real_sem_trywait(semaphore) == 0) return 0;
      errno = ETIMEDOUT;
      return -1;
    }
  }
}

void det_await_fd(int fd, short events, int flags) {
  if (!deterministic() || !holds_token()) return;
  if ((flags & MSG_DONTWAIT) != 0 || (::fcntl(fd, F_GETFL) & O_NONBLOCK) != 0) return;
  static const auto real_ppoll =
      shim::next_symbol<int (*)(pollfd*, nfds_t, const timespec*, const sigset_t*)>("ppoll");
  constexpr timespec kZero{0, 0};
  for (;;) {
    pollfd wanted{fd, events, 0};
    // Ready, or an error or hangup the call reports: it will not block. (A
    // plain look, not charged: it is not the program's call.)
    if (real_ppoll(&wanted, 1, &kZero, nullptr) != 0) return;
    poll_until(&wanted, 1, kNoDeadline, nullptr, ShimCall::BlockingCall);
  }
}

}  // namespace ubersim::timeshim::shim

namespace {

// Runs a call that may block in the kernel with the token handed over.
template <typename Call>
auto handing_over(Call&& call) {
  if (!shim::deterministic() || !shim::holds_token()) return call();
  shim::release_token();
  auto result = call();
  shim::acquire_token(shim::own_slot(), ShimCall::BlockingCall);
  shim::set_state(shim::own_slot(), ThreadState::Running, ShimCall::None, kNoDeadline);
  return result;
}

// After a kill, killpg, sigqueue or pthread_kill that returned `result`:
// a signal sent (not the probe signal 0) is counted, and the sender's turn
// ends.
int after_signal_sent(int result, int signal_number) {
  if (result != 0 || signal_number == 0) return result;
  if (Header* segment = shim::segment(); segment != nullptr) segment->signals_sent.fetch_add(1);
  handing_over([] { return 0; });
  return result;
}

struct ThreadStart {
  void* (*routine)(void*);
  void* argument;
  std::uint32_t order_id;
};

// A new thread of the group takes its place in the order its creator gave
// it, and waits for its first turn before the program's code runs.
void* start_in_turn(void* raw) {
  std::unique_ptr<ThreadStart> start(static_cast<ThreadStart*>(raw));
  shim::set_own_order(start->order_id);
  ThreadSlot& slot = shim::own_slot();
  shim::acquire_token(slot, ShimCall::ThreadStart);
  shim::set_state(slot, ThreadState::Running, ShimCall::None, kNoDeadline);
  void* (*routine)(void*) = start->routine;
  void* argument = start->argument;
  start.reset();
  return routine(argument);
}

}  // namespace

namespace ubersim::timeshim::shim {

int real_pthread_create(pthread_t* thread, const pthread_attr_t* attributes,
                        void* (*routine)(void*), void* argument) {
  static const auto next =
      shim::next_symbol<int (*)(pthread_t*, const pthread_attr_t*, void* (*)(void*), void*)>(
          "pthread_create");
  return next(thread, attributes, routine, argument);
}

}  // namespace ubersim::timeshim::shim

extern "C" {

__attribute__((visibility("default"))) int pthread_create(pthread_t* thread,
                                                          const pthread_attr_t* attributes,
                                                          void* (*routine)(void*), void* argument) {
  if (shim::segment() == nullptr || !shim::deterministic()) {
    return shim::real_pthread_create(thread, attributes, routine, argument);
  }
  auto start = std::make_unique<ThreadStart>(
      ThreadStart{routine, argument, shim::segment()->next_order_id.fetch_add(1)});
  const int result = shim::real_pthread_create(thread, attributes, start_in_turn, start.get());
  if (result == 0) static_cast<void>(start.release());
  return result;
}

__attribute__((visibility("default"))) int pthread_mutex_lock(pthread_mutex_t* mutex) {
  if (shim::segment() == nullptr || !shim::deterministic()) return real_mutex_lock(mutex);
  return shim::det_mutex_lock(mutex, kNoDeadline);
}

__attribute__((visibility("default"))) int pthread_mutex_unlock(pthread_mutex_t* mutex) {
  const int result = real_mutex_unlock(mutex);
  if (result == 0 && shim::deterministic()) {
    shim::det_wake(DetObject::Mutex, mutex, false, false);
    yield_to_woken();
  }
  return result;
}

__attribute__((visibility("default"))) int pthread_cond_wait(pthread_cond_t* cond,
                                                             pthread_mutex_t* mutex) {
  if (shim::segment() == nullptr || !shim::deterministic()) {
    static const auto next =
        shim::next_symbol<int (*)(pthread_cond_t*, pthread_mutex_t*)>("pthread_cond_wait");
    return next(cond, mutex);
  }
  return shim::det_cond_wait(cond, mutex, kNoDeadline);
}

__attribute__((visibility("default"))) int pthread_cond_signal(pthread_cond_t* cond) {
  static const auto next = shim::next_symbol<int (*)(pthread_cond_t*)>("pthread_cond_signal");
  if (shim::deterministic()) shim::det_wake(DetObject::Cond, cond, false, true);
  return next(cond);
}

__attribute__((visibility("default"))) int pthread_cond_broadcast(pthread_cond_t* cond) {
  static const auto next = shim::next_symbol<int (*)(pthread_cond_t*)>("pthread_cond_broadcast");
  if (shim::deterministic()) shim::det_wake(DetObject::Cond, cond, false, false);
  return next(cond);
}

__attribute__((visibility("default"))) int sem_wait(sem_t* semaphore) {
  if (shim::segment() == nullptr || !shim::deterministic()) {
    static const auto next = shim::next_symbol<int (*)(sem_t*)>("sem_wait");
    return next(semaphore);
  }
  return shim::det_sem_wait(semaphore, kNoDeadline);
}

__attribute__((visibility("default"))) int sem_post(sem_t* semaphore) noexcept {
  static const auto next = shim::next_symbol<int (*)(sem_t*)>("sem_post");
  const int result = next(semaphore);
  if (result == 0 && shim::deterministic()) {
    shim::det_wake(DetObject::Sem, semaphore, is_shared(semaphore), false);
    yield_to_woken();
  }
  return result;
}

__attribute__((visibility("default"))) int pthread_join(pthread_t thread, void** result) {
  static const auto next = shim::next_symbol<int (*)(pthread_t, void**)>("pthread_join");
  return handing_over([&] { return next(thread, result); });
}

__attribute__((visibility("default"))) pid_t waitpid(pid_t pid, int* status, int options) {
  static const auto next = shim::next_symbol<pid_t (*)(pid_t, int*, int)>("waitpid");
  if ((options & WNOHANG) != 0) return next(pid, status, options);
  return handing_over([&] { return next(pid, status, options); });
}

__attribute__((visibility("default"))) pid_t wait(int* status) {
  return waitpid(-1, status, 0);
}

__attribute__((visibility("default"))) pid_t wait4(pid_t pid, int* status, int options,
                                                   struct rusage* usage) noexcept {
  static const auto next = shim::next_symbol<pid_t (*)(pid_t, int*, int, struct rusage*)>("wait4");
  if ((options & WNOHANG) != 0) return next(pid, status, options, usage);
  return handing_over([&] { return next(pid, status, options, usage); });
}

__attribute__((visibility("default"))) pid_t wait3(int* status, int options,
                                                   struct rusage* usage) noexcept {
  return wait4(-1, status, options, usage);
}

__attribute__((visibility("default"))) int waitid(idtype_t type, id_t id, siginfo_t* info,
                                                  int options) {
  static const auto next = shim::next_symbol<int (*)(idtype_t, id_t, siginfo_t*, int)>("waitid");
  if ((options & WNOHANG) != 0) return next(type, id, info, options);
  return handing_over([&] { return next(type, id, info, options); });
}

__attribute__((visibility("default"))) int sigwaitinfo(const sigset_t* set, siginfo_t* info) {
  static const auto next = shim::next_symbol<int (*)(const sigset_t*, siginfo_t*)>("sigwaitinfo");
  return handing_over([&] { return next(set, info); });
}

__attribute__((visibility("default"))) int sigwait(const sigset_t* set, int* signal_number) {
  static const auto next = shim::next_symbol<int (*)(const sigset_t*, int*)>("sigwait");
  return handing_over([&] { return next(set, signal_number); });
}

// A signal takes effect at once on another core: the sender gives up its
// turn, so that by the next turn the signal has been handled, or its target
// has ended (and what ends with it, a pipe's last writer, shows), as on
// every run. The segment counts it: the controller's next look reads every
// thread (a signal may wake one that a light look would not read).
__attribute__((visibility("default"))) int kill(pid_t pid, int signal_number) noexcept {
  static const auto next = shim::next_symbol<int (*)(pid_t, int)>("kill");
  return after_signal_sent(next(pid, signal_number), signal_number);
}

__attribute__((visibility("default"))) int killpg(pid_t group, int signal_number) noexcept {
  static const auto next = shim::next_symbol<int (*)(pid_t, int)>("killpg");
  return after_signal_sent(next(group, signal_number), signal_number);
}

__attribute__((visibility("default"))) int sigqueue(pid_t pid, int signal_number,
                                                    const sigval value) noexcept {
  static const auto next = shim::next_symbol<int (*)(pid_t, int, const sigval)>("sigqueue");
  return after_signal_sent(next(pid, signal_number, value), signal_number);
}

__attribute__((visibility("default"))) int pthread_kill(pthread_t thread,
                                                        int signal_number) noexcept {
  static const auto next = shim::next_symbol<int (*)(pthread_t, int)>("pthread_kill");
  const int result = next(thread, signal_number);
  // pthread_kill returns an error number, 0 when sent.
  after_signal_sent(result == 0 ? 0 : -1, signal_number);
  return result;
}

// A thread that yields (a spin wait for another thread) lets the others
// that want to run have their turns first.
__attribute__((visibility("default"))) int sched_yield() noexcept {
  static const auto next = shim::next_symbol<int (*)()>("sched_yield");
  return handing_over([&] { return next(); });
}

__attribute__((visibility("default"))) int pause() {
  static const auto next = shim::next_symbol<int (*)()>("pause");
  return handing_over([&] { return next(); });
}

__attribute__((visibility("default"))) int sigsuspend(const sigset_t* mask) {
  static const auto next = shim::next_symbol<int (*)(const sigset_t*)>("sigsuspend");
  return handing_over([&] { return next(mask); });
}

}  // extern "C"
