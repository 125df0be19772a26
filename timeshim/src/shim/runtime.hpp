#pragma once
// The shim's state in one process (docs/timeshim.md): the mapped segment,
// this thread's slot and its view of sim time, and the waits every
// intercepted call is built from. Inactive (every call passes through to
// libc) when the process was started without UBERSIM_TIMESHIM_SHM.
#include <dlfcn.h>
#include <signal.h>
#include <time.h>

#include <cerrno>
#include <cstdint>

#include "ubersim/timeshim/shared_state.hpp"

namespace ubersim::timeshim::shim {

inline constexpr std::int64_t kNsPerSecond = 1000000000;
// The fds the shim keeps per-fd state for (timers, socket timeouts); a higher fd
// keeps the kernel's wall-time behaviour.
inline constexpr int kMaxFd = 65536;

// The next definition of `name` after the shim (libc's), resolved once.
template <typename Fn>
Fn next_symbol(const char* name) {
  return reinterpret_cast<Fn>(::dlsym(RTLD_NEXT, name));
}

// The segment, or nullptr when the shim is inactive.
Header* segment();

// Sim time as this thread sees it: the group's sim time, never before what
// this thread saw last, plus what it was charged since it last blocked.
std::int64_t view_now();
// view_now() for a call that reads the clock: charges it, and pauses a
// thread that has run too far ahead of sim time without blocking.
std::int64_t read_clock();
// A non-blocking intercepted call (a zero timeout): charged like a clock read.
void charge_call();

// This thread's slot (claimed at its first use).
ThreadSlot& own_slot();
// A slot for something that is not a thread (a timer) of this process, or
// nullptr when all are taken.
ThreadSlot* claim_other_slot();
void release_other_slot(ThreadSlot& slot);
// Wakes the controller to look again.
void notify();
// Starts this process's helper thread (after a fork, the child's own) if it
// has none: it wakes condition variable waiters and fires timers.
void ensure_helper();
// Says what this thread does now (and wakes the controller to look).
void set_state(ThreadSlot& slot, ThreadState state, ShimCall call, std::int64_t deadline_ns);
// After a block that began when the thread saw view_at_start and reached
// sim time reached_ns (0: not known): the view does not go back, and the
// charge is forgiven.
void after_block(std::int64_t view_at_start, std::int64_t reached_ns, ShimCall call);

// Deterministic mode (docs/timeshim.md): the group's threads run one at a
// time, each in its turn, which the controller grants in a fixed order.
bool deterministic();
// Deterministic mode: this thread is about to make a call that can end
// another thread's wait for an fd, one the kernel does not count among its
// writes (/proc/<tid>/io's syscw): a send, connect, shutdown or close
// (Header::fd_outputs).
void note_fd_output();
// This thread's place in the order, given by its creator before its slot.
void set_own_order(std::uint32_t order_id);
// Gives up the run token (before a thread blocks); no-op when not held or
// not in deterministic mode.
void release_token();
bool holds_token();
// Says what this thread waits for now (as set_state) and ends its turn if it
// holds the token: hands it to the next thread itself when the turn changed
// nothing a look relies on (handoff.cpp), else gives it back to the controller.
void end_turn(ThreadSlot& slot, ThreadState state, ShimCall call, std::int64_t deadline_ns);
// Waits for this thread's turn (after a block, before the program's code
// runs again); says so in the slot (WantToken). Keeps errno.
void acquire_token(ThreadSlot& slot, ShimCall call);
// Waits until the controller grants this thread the token (its state says
// why it waits: WantToken, or DetBlocked until a peer makes it WantToken).
void wait_for_turn(ThreadSlot& slot);

// Sleeps until sim time reaches deadline_ns. Returns 0, or EINTR when a
// signal of the program's own interrupted it (then sim time is before it).
int sleep_until(std::int64_t deadline_ns, ShimCall call);

// Runs a wait for fds or a semaphore until it returns or sim time reaches
// deadline_ns (kNoDeadline: no limit). `block` is called with the signal mask
// to wait with (the thread's own, or `wait_mask`, without the wake signal) and
// blocks for at most kLivenessCheck of wall time; it returns > 0 when its wait
// ended (ready), 0 when the wall limit passed (then the controller's life is
// checked and it is called again), or -1 with errno. Returns block's result,
// or 0 with errno untouched when the deadline came first. `*timed_out` says
// which.
template <typename Block>
int wait_until(std::int64_t deadline_ns, ShimCall call, ThreadState state,
               const sigset_t* wait_mask, bool* timed_out, Block&& block);

// How long a shim wait blocks in the kernel before it checks that the
// controller still runs (with it gone, sim time never advances again).
inline constexpr timespec kLivenessCheck{1, 0};
inline constexpr int kLivenessCheckMs = 1000;
// Says so and ends the process when the controller is gone: a wait for sim
// time would never end (never a silent hang).
void exit_if_controller_gone();
// kLivenessCheck from now on the kernel's CLOCK_MONOTONIC (for the waits
// that take an absolute time).
timespec wall_liveness_deadline();
// The kernel's CLOCK_MONOTONIC (wall time, not sim time), in ns.
std::int64_t wall_monotonic_ns();

// Parts of wait_until that need no template.
struct WaitScope {
  WaitScope(std::int64_t deadline_ns, ShimCall call, ThreadState state, const sigset_t* wait_mask);
  ~WaitScope();
  WaitScope(const WaitScope&) = delete;
  WaitScope& operator=(const WaitScope&) = delete;
  bool deadline_passed() const;
  // Clears and returns whether the wake signal arrived since the last call.
  bool take_wake();
  void set_timed_out() { timed_out_ = true; }
  const sigset_t* mask() const { return &mask_; }

 private:
  std::int64_t deadline_ns_;
  std::int64_t view_at_start_;
  ShimCall call_ = ShimCall::None;
  bool timed_out_ = false;
  sigset_t mask_{};
};

template <typename Block>
int wait_until(std::int64_t deadline_ns, ShimCall call, ThreadState state,
               const sigset_t* wait_mask, bool* timed_out, Block&& block) {
  WaitScope scope(deadline_ns, call, state, wait_mask);
  *timed_out = false;
  for (;;) {
    if (scope.deadline_passed()) {
      scope.set_timed_out();
      *timed_out = true;
      return 0;
    }
    const int result = block(scope.mask());
    if (result > 0) return result;
    if (result == 0) {
      exit_if_controller_gone();
      continue;
    }
    // Our wake signal: look at the deadline again. The program's own signal
    // (EINTR without ours) or an error goes back to the program.
    if (errno == EINTR && scope.take_wake()) continue;
    if (errno == EINTR && scope.deadline_passed()) continue;
    return result;
  }
}

// Sim time <-> struct timespec for the clock ids the shim serves; false for
// the ids it passes to the kernel (CPU-time clocks).
bool sim_clock(clockid_t clock, std::int64_t* offset_ns);

inline std::int64_t to_ns(const timespec& t) {
  return static_cast<std::int64_t>(t.tv_sec) * kNsPerSecond + t.tv_nsec;
}
inline timespec to_timespec(std::int64_t ns) {
  timespec t{};
  t.tv_sec = static_cast<time_t>(ns / kNsPerSecond);
  t.tv_nsec = static_cast<long>(ns % kNsPerSecond);
  if (t.tv_nsec < 0) {
    t.tv_nsec += kNsPerSecond;
    t.tv_sec -= 1;
  }
  return t;
}
// a + b, saturating at kNoDeadline.
inline std::int64_t deadline_after(std::int64_t now_ns, std::int64_t duration_ns) {
  if (duration_ns >= kNoDeadline - now_ns) return kNoDeadline;
  return now_ns + duration_ns;
}

}  // namespace ubersim::timeshim::shim
