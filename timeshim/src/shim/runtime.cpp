// The shim's per-process and per-thread state (runtime.hpp).
#include "runtime.hpp"

#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>

#include "handoff.hpp"

namespace ubersim::timeshim::shim {
namespace {

// What the shim keeps per thread. Trivial, so that initial-exec TLS needs no
// constructor and a call from any context (a signal handler, another
// library's constructor) can use it.
struct ThreadRecord {
  ThreadSlot* slot;
  pid_t tid;
  std::int64_t floor_ns;   // the view never goes below this (what it saw last)
  std::int64_t charge_ns;  // charged since the last block
  std::int64_t free_calls_used;
  std::uint32_t order_id;  // deterministic mode: its place in the order, when given before its slot
  bool has_order;
  bool had_token;  // deterministic mode: it got the token and did not give it up
};

__attribute__((tls_model("initial-exec"))) thread_local ThreadRecord this_thread{};
__attribute__((tls_model("initial-exec"))) thread_local volatile sig_atomic_t wake_arrived = 0;

// Calls a thread may make after each block before it is charged: enough
// that a program which blocks now and then is never charged (CPython's
// start reads the clock about 700 times), so that what it sees does not
// depend on how many calls the scheduler let it make.
constexpr std::int64_t kFreeCalls = 2000;

Header* the_segment = nullptr;
pthread_key_t slot_key;

// The token holder's changes need no wake-up: the controller waits for the
// turn's end, which release_token says (or for the holder's hand-over,
// handoff.cpp), and a wake-up in each turn would cost it a core.
void notify_controller() {
  the_segment->change_seq.fetch_add(1);
  if (!holds_token()) futex_wake_all(the_segment->change_seq);
}

// The order id of a forked child, given out by the parent (which holds the
// run token) in the prepare handler.
std::uint32_t fork_child_order = 0;

void release_slot(void* slot_ptr) {
  auto* slot = static_cast<ThreadSlot*>(slot_ptr);
  if (slot == nullptr || the_segment == nullptr) return;
  slot->state.store(static_cast<std::uint32_t>(ThreadState::Free));
  slot->tid.store(0);
  slot->claim.store(0);
  notify_controller();
}

// A thread that ends holding the run token (deterministic mode) keeps it
// and its slot to its very end: the controller takes both back once the
// thread is gone (turns.cpp), so that nothing it still does (other
// destructors, libc's cleanup) runs beside the next turn.
void on_thread_exit(void* slot_ptr) {
  auto* slot = static_cast<ThreadSlot*>(slot_ptr);
  if (slot != nullptr && the_segment != nullptr && the_segment->deterministic != 0 &&
      the_segment->token_tid.load() == slot->tid.load()) {
    return;
  }
  release_slot(slot_ptr);
}

void on_wake_signal(int /*signal*/) {
  wake_arrived = 1;
}

void block_wake_signal() {
  sigset_t wake{};
  sigemptyset(&wake);
  sigaddset(&wake, the_segment->wake_signal);
  pthread_sigmask(SIG_BLOCK, &wake, nullptr);
}

// A slot for this thread: after exec or fork a slot may still carry this
// tid (the image before it); it is this thread's no longer.
// Makes a slot just claimed part of used_slots (before its tid or timer is
// set: the controller looks at a slot only then).
void count_as_used(const ThreadSlot& slot) {
  const auto used = static_cast<std::uint32_t>(&slot - the_segment->threads) + 1;
  std::uint32_t seen = the_segment->slots_used.load();
  while (seen < used && !the_segment->slots_used.compare_exchange_weak(seen, used)) {
  }
}

ThreadSlot* claim_slot(pid_t tid) {
  std::uint32_t order = this_thread.order_id;
  bool has_order = this_thread.has_order;
  for (auto& slot : used_slots(*the_segment)) {
    if (slot.claim.load() != 0 && slot.tid.load() == tid) {
      // The same thread in a new image (exec) keeps its place.
      if (!has_order) order = slot.order_id.load();
      has_order = true;
      release_slot(&slot);
    }
  }
  // The group's first thread, or a process exec'd from a vfork or
  // posix_spawn child (no fork handler ran): the next place in the order.
  if (!has_order) order = the_segment->next_order_id.fetch_add(1);
  for (auto& slot : the_segment->threads) {
    std::uint32_t free_claim = 0;
    if (!slot.claim.compare_exchange_strong(free_claim, 1)) continue;
    count_as_used(slot);
    // tid last: until it is set the controller leaves the slot alone.
    slot.pid.store(static_cast<std::int32_t>(::getpid()));
    slot.deadline_ns.store(kNoDeadline);
    slot.call.store(static_cast<std::uint32_t>(ShimCall::None));
    slot.order_id.store(order);
    slot.ready_seq.store(0);
    slot.det_object.store(0);
    slot.state.store(static_cast<std::uint32_t>(ThreadState::Running));
    slot.tid.store(static_cast<std::int32_t>(tid));
    return &slot;
  }
  std::fprintf(stderr, "ubersim timeshim: more than %d threads in the group; stopping\n",
               kMaxThreads);
  std::abort();
}

}  // namespace

ThreadSlot* claim_other_slot() {
  for (auto& slot : the_segment->threads) {
    std::uint32_t free_claim = 0;
    if (!slot.claim.compare_exchange_strong(free_claim, 1)) continue;
    count_as_used(slot);
    slot.pid.store(static_cast<std::int32_t>(::getpid()));
    slot.deadline_ns.store(kNoDeadline);
    return &slot;
  }
  return nullptr;
}

void release_other_slot(ThreadSlot& slot) {
  release_slot(&slot);
}

void notify() {
  notify_controller();
}

ThreadSlot& own_slot() {
  if (this_thread.slot == nullptr) {
    this_thread.tid = static_cast<pid_t>(::syscall(SYS_gettid));
    this_thread.slot = claim_slot(this_thread.tid);
    block_wake_signal();
    pthread_setspecific(slot_key, this_thread.slot);
    notify_controller();
  }
  return *this_thread.slot;
}

void set_state(ThreadSlot& slot, ThreadState state, ShimCall call, std::int64_t deadline_ns) {
  slot.deadline_ns.store(deadline_ns);
  slot.call.store(static_cast<std::uint32_t>(call));
  slot.state.store(static_cast<std::uint32_t>(state));
  notify_controller();
}

// After a block: the view does not go back, and the charge is forgiven. A
// charged pause is no block: the free calls stay used.
void after_block(std::int64_t view_at_start, std::int64_t reached_ns, ShimCall call) {
  this_thread.floor_ns = std::max({this_thread.floor_ns, view_at_start, reached_ns});
  this_thread.charge_ns = 0;
  if (call != ShimCall::ChargedYield) this_thread.free_calls_used = 0;
}

namespace {

// The parent holds the run token while it forks (deterministic mode): the
// child's place in the order is given out now, the same on every run.
void order_for_child() {
  if (the_segment != nullptr && the_segment->deterministic != 0) {
    fork_child_order = the_segment->next_order_id.fetch_add(1);
  }
}

void forget_slot_in_child() {
  // The forked child's only thread is a new thread: its own slot, later;
  // in deterministic mode now, to wait for its first turn.
  this_thread.slot = nullptr;
  this_thread.tid = 0;
  if (the_segment != nullptr && the_segment->deterministic != 0) {
    this_thread.order_id = fork_child_order;
    this_thread.has_order = true;
    acquire_token(own_slot(), ShimCall::ThreadStart);
    set_state(own_slot(), ThreadState::Running, ShimCall::None, kNoDeadline);
  }
}

[[noreturn]] void fail_attach(const char* path, const char* what) {
  std::fprintf(stderr, "ubersim timeshim: cannot attach to the controller's segment %s: %s\n", path,
               what);
  ::_exit(127);
}

Header* attach(const char* path) {
  const int fd = ::open(path, O_RDWR | O_CLOEXEC);
  if (fd < 0) fail_attach(path, "cannot open it");
  struct stat info {};
  if (::fstat(fd, &info) != 0 || info.st_size < static_cast<off_t>(sizeof(Header))) {
    ::close(fd);
    fail_attach(path, "it is too small");
  }
  void* mapped = ::mmap(nullptr, sizeof(Header), PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
  ::close(fd);
  if (mapped == MAP_FAILED) fail_attach(path, "mmap failed");
  auto* header = static_cast<Header*>(mapped);
  if (header->magic != kMagic || header->version != kVersion) {
    fail_attach(path, "not a time shim segment of this version");
  }
  return header;
}

void start_shim() {
  const char* path = std::getenv(kSegmentEnv);
  if (path == nullptr || *path == '\0') return;
  Header* header = attach(path);
  pthread_key_create(&slot_key, on_thread_exit);
  pthread_atfork(order_for_child, nullptr, forget_slot_in_child);
  struct sigaction action {};
  action.sa_handler = on_wake_signal;
  // No SA_RESTART: the kernel would restart a futex wait (sem_wait) after
  // the handler. The signal is blocked outside the shim's waits anyway.
  action.sa_flags = 0;
  sigemptyset(&action.sa_mask);
  sigaction(header->wake_signal, &action, nullptr);
  the_segment = header;
  ThreadSlot& slot = own_slot();
  // Deterministic mode: the program's code runs only in its turn (after an
  // exec, this thread may hold the token already).
  acquire_token(slot, ShimCall::ThreadStart);
  set_state(slot, ThreadState::Running, ShimCall::None, kNoDeadline);
}

pthread_once_t started = PTHREAD_ONCE_INIT;
std::atomic<bool> start_done{false};

void start_once() {
  start_shim();
  start_done.store(true, std::memory_order_release);
}

// At load; or earlier, at the first intercepted call, when another library's
// constructor reads the clock before this one ran.
__attribute__((constructor)) void start_at_load() {
  pthread_once(&started, start_once);
}

}  // namespace

void exit_if_controller_gone() {
  const int saved = errno;
  const pid_t controller = the_segment->controller_pid;
  if (::kill(controller, 0) != 0 && errno == ESRCH) {
    std::fprintf(stderr,
                 "ubersim timeshim: process %d: the controller (pid %d) is gone, so sim time "
                 "cannot advance; exiting\n",
                 static_cast<int>(::getpid()), static_cast<int>(controller));
    ::_exit(124);
  }
  errno = saved;
}

std::int64_t wall_monotonic_ns() {
  static const auto real_clock = next_symbol<int (*)(clockid_t, timespec*)>("clock_gettime");
  timespec now{};
  real_clock(CLOCK_MONOTONIC, &now);
  return to_ns(now);
}

timespec wall_liveness_deadline() {
  return to_timespec(wall_monotonic_ns() + to_ns(kLivenessCheck));
}

Header* segment() {
  if (!start_done.load(std::memory_order_acquire)) pthread_once(&started, start_once);
  return the_segment;
}

bool deterministic() {
  return the_segment != nullptr && the_segment->deterministic != 0;
}

void note_fd_output() {
  if (deterministic()) the_segment->fd_outputs.fetch_add(1, std::memory_order_relaxed);
}

void set_own_order(std::uint32_t order_id) {
  this_thread.order_id = order_id;
  this_thread.has_order = true;
}

namespace {

void give_token_back() {
  this_thread.had_token = false;
  if (!deterministic() || this_thread.slot == nullptr) return;
  std::int32_t tid = this_thread.tid;
  if (the_segment->token_tid.compare_exchange_strong(tid, 0)) notify_controller();
}

}  // namespace

void release_token() {
  forget_turn_writes();
  give_token_back();
}

void end_turn(ThreadSlot& slot, ThreadState state, ShimCall call, std::int64_t deadline_ns) {
  set_state(slot, state, call, deadline_ns);
  if (!deterministic() || !holds_token()) {
    release_token();
  } else if (hand_off_turn(*the_segment, slot, this_thread.tid)) {
    this_thread.had_token = false;
  } else {
    give_token_back();
  }
}

bool holds_token() {
  return this_thread.slot != nullptr && the_segment->token_tid.load() == this_thread.tid;
}

void wait_for_turn(ThreadSlot& slot) {
  for (;;) {
    const std::uint32_t seq = slot.wake_seq.load();
    if (the_segment->token_tid.load() == this_thread.tid) {
      note_turn_start(*the_segment);
      return;
    }
    const long waited = futex_wait(slot.wake_seq, seq, to_ns(kLivenessCheck));
    if (waited != 0 && errno == ETIMEDOUT) exit_if_controller_gone();
  }
}

void acquire_token(ThreadSlot& slot, ShimCall call) {
  if (!deterministic()) return;
  if (!holds_token()) {
    const int saved = errno;
    // (Already said when its turn ended wanting the next: end_turn.)
    if (slot.state.load() != static_cast<std::uint32_t>(ThreadState::WantToken)) {
      set_state(slot, ThreadState::WantToken, call, kNoDeadline);
    }
    wait_for_turn(slot);
    errno = saved;
  }
  this_thread.had_token = true;
}

namespace {

// The controller took the token from this thread while it was blocked in a
// call that did not hand it over (turns.cpp): it waits for a turn now.
void rejoin_turns() {
  if (!this_thread.had_token || holds_token()) return;
  this_thread.had_token = false;
  ThreadSlot& slot = own_slot();
  acquire_token(slot, ShimCall::BlockingCall);
  set_state(slot, ThreadState::Running, ShimCall::None, kNoDeadline);
}

}  // namespace

std::int64_t view_now() {
  const std::int64_t sim_now = the_segment->sim_now_ns.load();
  return std::max(sim_now, this_thread.floor_ns) + this_thread.charge_ns;
}

void charge_call() {
  the_segment->intercepted_calls.fetch_add(1, std::memory_order_relaxed);
  if (the_segment->deterministic != 0) rejoin_turns();
  if (this_thread.free_calls_used < kFreeCalls) {
    ++this_thread.free_calls_used;
    return;
  }
  this_thread.charge_ns += the_segment->charge_ns;
  const std::int64_t yield_after = the_segment->yield_after_ns;
  if (yield_after > 0 && this_thread.charge_ns >= yield_after) {
    // Run no further ahead: wait until sim time reaches what this thread sees,
    // rounded up to a multiple of yield_after, so that the polling threads of
    // a group pause at the same instants and sim time advances once for all
    // of them (not once per thread: each advance costs the controller two
    // looks at every thread).
    const std::int64_t view = view_now();
    the_segment->charged_pauses.fetch_add(1, std::memory_order_relaxed);
    sleep_until((view + yield_after - 1) / yield_after * yield_after, ShimCall::ChargedYield);
  }
}

std::int64_t read_clock() {
  const std::int64_t now = view_now();
  charge_call();
  return now;
}

int sleep_until(std::int64_t deadline_ns, ShimCall call) {
  const std::int64_t view_at_start = view_now();
  ThreadSlot& slot = own_slot();
  end_turn(slot, ThreadState::Sleeping, call, deadline_ns);
  int result = 0;
  for (;;) {
    const std::uint32_t seq = slot.wake_seq.load();
    if (the_segment->sim_now_ns.load() >= deadline_ns) break;
    const long waited = futex_wait(slot.wake_seq, seq, to_ns(kLivenessCheck));
    if (waited != 0 && errno == EINTR) {
      result = EINTR;
      break;
    }
    if (waited != 0 && errno == ETIMEDOUT) exit_if_controller_gone();
  }
  acquire_token(slot, call);
  set_state(slot, ThreadState::Running, ShimCall::None, kNoDeadline);
  after_block(view_at_start, result == 0 ? deadline_ns : 0, call);
  return result;
}

WaitScope::WaitScope(std::int64_t deadline_ns, ShimCall call, ThreadState state,
                     const sigset_t* wait_mask)
    : deadline_ns_(deadline_ns), view_at_start_(view_now()) {
  ThreadSlot& slot = own_slot();
  if (wait_mask != nullptr) {
    mask_ = *wait_mask;
  } else {
    pthread_sigmask(SIG_BLOCK, nullptr, &mask_);
  }
  sigdelset(&mask_, the_segment->wake_signal);
  wake_arrived = 0;
  call_ = call;
  end_turn(slot, state, call, deadline_ns);
}

WaitScope::~WaitScope() {
  acquire_token(*this_thread.slot, call_);
  set_state(*this_thread.slot, ThreadState::Running, ShimCall::None, kNoDeadline);
  after_block(view_at_start_, timed_out_ ? deadline_ns_ : 0, ShimCall::None);
}

bool WaitScope::deadline_passed() const {
  return deadline_ns_ != kNoDeadline && the_segment->sim_now_ns.load() >= deadline_ns_;
}

bool WaitScope::take_wake() {
  const bool arrived = wake_arrived != 0;
  wake_arrived = 0;
  return arrived;
}

bool sim_clock(clockid_t clock, std::int64_t* offset_ns) {
  switch (clock) {
    case CLOCK_REALTIME:
    case CLOCK_REALTIME_COARSE:
    case CLOCK_REALTIME_ALARM:
      *offset_ns = the_segment->realtime_epoch_ns;
      return true;
    case CLOCK_TAI:
      // TAI is ahead of UTC by 37 s since 2017.
      *offset_ns = the_segment->realtime_epoch_ns + 37 * kNsPerSecond;
      return true;
    case CLOCK_MONOTONIC:
    case CLOCK_MONOTONIC_RAW:
    case CLOCK_MONOTONIC_COARSE:
    case CLOCK_BOOTTIME:
    case CLOCK_BOOTTIME_ALARM:
      *offset_ns = 0;
      return true;
    default:
      return false;  // CPU-time clocks: what the thread really consumed
  }
}

}  // namespace ubersim::timeshim::shim
