#pragma once
// The time shim's shared memory segment (docs/timeshim.md): what the
// controller and every shimmed thread of its group read and write. The
// controller creates it (a file it maps, its path in UBERSIM_TIMESHIM_SHM);
// each process the shim is loaded into maps it at start.
//
// Plain data with lock-free atomics only, so that it means the same in every
// process that maps it (no pointers, no locks: a process may die anywhere).
#include <sys/types.h>

#include <atomic>
#include <cstdint>
#include <limits>

namespace ubersim::timeshim {

// The environment variable that names the segment's file.
inline constexpr const char* kSegmentEnv = "UBERSIM_TIMESHIM_SHM";
inline constexpr std::uint32_t kMagic = 0x54534d55;  // "UMST"
inline constexpr std::uint32_t kVersion = 7;
inline constexpr int kMaxThreads = 1024;
// No deadline: a wait only input can end.
inline constexpr std::int64_t kNoDeadline = std::numeric_limits<std::int64_t>::max();

// What a thread is doing, as the shim last said.
enum class ThreadState : std::uint32_t {
  Free = 0,         // slot unused
  Running = 1,      // in the program's own code (or in a call the shim does not know)
  Sleeping = 2,     // in a shim sleep until deadline_ns (woken by a futex on wake_seq)
  WaitingFd = 3,    // in a shim wait for fd readiness, until deadline_ns (woken by kWakeSignal)
  WaitingSem = 4,   // in a shim semaphore wait, until deadline_ns (woken by kWakeSignal)
  WaitingCond = 5,  // in a shim condition variable wait, until deadline_ns (woken by the helper)
  Helper = 6,       // the shim's helper thread of a process (it wakes WaitingCond threads)
  Timer = 7,        // not a thread: a timer of process pid (timer_kind), due at deadline_ns
  // Deterministic mode (docs/timeshim.md): the thread waits for the run token,
  // which the controller grants in a fixed order once the group is quiescent.
  WantToken = 8,
  // Deterministic mode: waits in the shim for a peer (a mutex, condition
  // variable or semaphore, cond_addr) or for deadline_ns; a peer's unlock,
  // signal or post, or the controller at the deadline, makes it WantToken.
  DetBlocked = 9,
};

// What a Timer slot is.
enum class TimerKind : std::uint32_t {
  Fd = 0,     // a timerfd: expirations go to the eventfd timer_fd
  Posix = 1,  // timer_create: a signal (SIGEV_SIGNAL, _THREAD_ID) or a thread (SIGEV_THREAD)
};

// What a DetBlocked thread waits for.
enum class DetObject : std::uint32_t { None = 0, Mutex, Cond, Sem };

// Which intercepted call a thread is blocked in, for the messages that name it.
enum class ShimCall : std::uint32_t {
  None = 0,
  Nanosleep,
  ClockNanosleep,
  Usleep,
  Sleep,
  Select,
  Pselect,
  Poll,
  Ppoll,
  EpollWait,
  EpollPwait,
  SemTimedwait,
  CondTimedwait,
  SocketReceive,  // a receive on a socket with SO_RCVTIMEO
  ChargedYield,   // the pause a thread that never blocks is given (charged calls)
  MutexLock,      // pthread_mutex_lock (deterministic mode), _timedlock, _clocklock
  CondWait,       // pthread_cond_wait (deterministic mode)
  SemWait,        // sem_wait (deterministic mode)
  ThreadStart,    // a new thread or process waiting for its first turn (deterministic mode)
  BlockingCall,   // a blocking call the token is handed over in (deterministic mode)
  SocketSend,     // a send on a socket with SO_SNDTIMEO
  Accept,         // accept on a socket with SO_RCVTIMEO
  SigTimedwait,   // sigtimedwait
  EpollPwait2,    // epoll_pwait2
};

const char* shim_call_name(ShimCall call);

// Deterministic mode's waits that only the controller (a turn) or the token
// holder (a peer's unlock, signal or post, which says so in the segment) can
// end: the thread runs nothing of the program until it gets the token, so
// what the kernel says of it does not matter, and a look need not read it.
inline bool ends_only_in_turn(ThreadState state) {
  return state == ThreadState::WantToken || state == ThreadState::DetBlocked;
}

// A wait only the controller, the token holder or a signal can end.
inline bool ends_without_input(ThreadState state) {
  return ends_only_in_turn(state) || state == ThreadState::Sleeping;
}

// A wait for fds that input ends (not sigtimedwait's, a wait for a signal,
// which checks for a pending signal only in the kernel).
inline bool waits_for_input(ThreadState state, ShimCall call) {
  return state == ThreadState::WaitingFd && call != ShimCall::SigTimedwait;
}

// Deterministic mode: a state a turn's thread gives the token back in when
// what it does next is not the program's: it waits for its turn, a peer, sim
// time, or input. For input, whether any was there it checked holding the
// token, and nobody but it ran since: only input from outside the group can
// end that wait now, at a time no look can make the same on every run. The
// controller's light look and the shim's hand-over both judge the end of a
// turn by it.
inline bool settled_after_turn(ThreadState state, ShimCall call) {
  return ends_without_input(state) || waits_for_input(state, call);
}

struct alignas(64) ThreadSlot {
  std::atomic<std::uint32_t> state{0};     // ThreadState
  std::atomic<std::uint32_t> wake_seq{0};  // futex: the controller bumps it to wake a sleeper
  std::atomic<std::int32_t> pid{0};
  std::atomic<std::int32_t> tid{0};
  std::atomic<std::int64_t> deadline_ns{kNoDeadline};  // sim time the wait ends at
  std::atomic<std::uint32_t> call{0};                  // ShimCall
  std::atomic<std::uint32_t> claim{0};                 // 0 free, 1 taken (CAS to allocate)
  // WaitingCond: the condition variable (an address in the thread's process)
  // and the helper's pin on it (the waiter does not leave while it is set).
  std::atomic<std::uint64_t> cond_addr{0};
  std::atomic<std::uint32_t> pin{0};
  // Timer: its fd (an eventfd the helper writes expirations to) and period.
  std::atomic<std::int32_t> timer_fd{-1};
  std::atomic<std::int64_t> interval_ns{0};
  // Timer: TimerKind, and for Posix: how it notifies (sigev_notify), the
  // signal, its value, the function of SIGEV_THREAD, the thread of
  // SIGEV_THREAD_ID, and the overrun of its last expiry.
  std::atomic<std::uint32_t> timer_kind{0};
  std::atomic<std::int32_t> timer_notify{0};
  std::atomic<std::int32_t> timer_signal{0};
  std::atomic<std::uint64_t> timer_value{0};
  std::atomic<std::uint64_t> timer_function{0};
  std::atomic<std::int32_t> timer_tid{0};
  std::atomic<std::int32_t> timer_overrun{0};
  // Deterministic mode: the thread's place in the fixed order (creation
  // order in the group, not the kernel's tid), what a DetBlocked thread
  // waits for (DetObject; cond_addr is the object, det_shared when it is a
  // process-shared semaphore), whether a peer ended that wait, the FIFO
  // position of a condition waiter, and the order in which the controller
  // saw it want the token (0: not yet).
  std::atomic<std::uint32_t> order_id{0};
  std::atomic<std::uint32_t> det_object{0};
  std::atomic<std::uint32_t> det_shared{0};
  std::atomic<std::uint32_t> det_signaled{0};
  std::atomic<std::uint64_t> det_wait_seq{0};
  std::atomic<std::uint64_t> ready_seq{0};
};

struct Header {
  std::uint32_t magic = 0;
  std::uint32_t version = 0;
  std::uint64_t size = 0;  // bytes of the whole segment
  // Simulation time now, ns since the group's start. Only the controller writes it.
  std::atomic<std::int64_t> sim_now_ns{0};
  // CLOCK_REALTIME = realtime_epoch_ns + sim time.
  std::int64_t realtime_epoch_ns = 0;
  // Sim time charged per intercepted call that does not block, and how much
  // charge a thread may run ahead before it pauses until sim time catches up.
  std::int64_t charge_ns = 0;
  std::int64_t yield_after_ns = 0;
  // The signal that interrupts a shim fd or semaphore wait whose deadline passed.
  std::int32_t wake_signal = 0;
  std::int32_t controller_pid = 0;
  // Bumped (and futex-woken) by the shim at every change of a thread's state:
  // the controller sleeps on it.
  std::atomic<std::uint32_t> change_seq{0};
  std::atomic<std::uint64_t> intercepted_calls{0};
  // Pauses of threads that polled without blocking until their charge
  // reached yield_after_ns: how much of the group's time goes to polling.
  std::atomic<std::uint64_t> charged_pauses{0};
  // Signals the group's threads sent (kill, killpg, sigqueue, pthread_kill):
  // a signal can wake a thread that a light look (deterministic mode) does
  // not read, so the look after one reads every thread.
  std::atomic<std::uint64_t> signals_sent{0};
  // Deterministic mode: calls of the group's threads that can end another
  // thread's wait for an fd (a write, send, connect, shutdown or close; the
  // shim's interposers count them): a light look after a turn that made
  // none need not read the threads that wait for fds (light_look.cpp).
  std::atomic<std::uint64_t> fd_outputs{0};
  // Deterministic mode: on (1) or off (0), set before any process attaches;
  // the tid of the thread that holds the run token (0: none); the next
  // thread's place in the order (given out by the token holder, so the same
  // on every run); DetBlocked threads (a peer's unlock looks for waiters
  // only when there are any); the FIFO counter of condition waits; the
  // controller's counter of turns.
  std::uint32_t deterministic = 0;
  std::atomic<std::int32_t> token_tid{0};
  std::atomic<std::uint32_t> next_order_id{0};
  std::atomic<std::uint32_t> det_blocked{0};
  std::atomic<std::uint64_t> det_wait_counter{0};
  std::atomic<std::uint64_t> ready_counter{0};
  std::atomic<std::uint64_t> turns{0};
  // Deterministic mode, turns handed over by the shim (shim/handoff.cpp):
  // the controller allows them (1) when the look that gave the last turn
  // found every thread of the group in a shim wait, and says what a turn
  // must leave as it is for the next one to need no look: the host's last
  // pid and the group's signals sent as at its last full look, and until
  // when (CLOCK_MONOTONIC, ns) that look is recent enough. The shim counts
  // the turns it handed over and names the thread it handed the last to.
  std::atomic<std::uint32_t> handoff_allowed{0};
  std::atomic<std::int64_t> handoff_last_pid{0};
  std::atomic<std::uint64_t> handoff_signals_sent{0};
  std::atomic<std::int64_t> handoff_until_ns{0};
  std::atomic<std::uint64_t> handoffs{0};
  std::atomic<std::int32_t> handoff_tid{0};
  // One past the highest slot ever claimed: the slots after it were never
  // used, so loops over the group's threads stop there (every unlock in
  // deterministic mode loops over them).
  std::atomic<std::uint32_t> slots_used{0};
  ThreadSlot threads[kMaxThreads];
};

// The slots of `header` that threads have claimed so far (some may be free
// again), for range-for.
struct UsedSlots {
  ThreadSlot* first;
  ThreadSlot* last;
  ThreadSlot* begin() const { return first; }
  ThreadSlot* end() const { return last; }
};
inline UsedSlots used_slots(Header& header) {
  const std::uint32_t used = header.slots_used.load();
  return UsedSlots{header.threads, header.threads + (used < kMaxThreads ? used : kMaxThreads)};
}

static_assert(std::atomic<std::int64_t>::is_always_lock_free);
static_assert(std::atomic<std::uint32_t>::is_always_lock_free);
static_assert(sizeof(std::atomic<std::uint32_t>) == sizeof(std::uint32_t));  // futex words

// Deterministic mode: the next place in the queue for the token (1, 2, ...;
// 0 in a slot means none yet).
inline std::uint64_t next_ready_place(Header& header) {
  return header.ready_counter.fetch_add(1) + 1;
}

// Blocking states: the thread waits in the shim (and, once the kernel says it
// sleeps, counts as waiting for the controller).
inline bool is_shim_wait(ThreadState state) {
  return state == ThreadState::Sleeping || state == ThreadState::WaitingFd ||
         state == ThreadState::WaitingSem || state == ThreadState::WaitingCond ||
         state == ThreadState::WantToken || state == ThreadState::DetBlocked;
}

// Futex calls on a shared mapping (not FUTEX_PRIVATE: several processes).
// timeout_ns < 0: no timeout. Returns the syscall's result (errno set).
long futex_wait(std::atomic<std::uint32_t>& word, std::uint32_t expected, long timeout_ns);
void futex_wake_all(std::atomic<std::uint32_t>& word);

// Deterministic mode: the thread that now holds the run token (Running, and
// in token_tid) starts its turn: the turn is counted and the thread woken
// from its wait for the token. The controller's give_turn and the shim's
// hand-over both end so.
void start_turn(Header& segment, ThreadSlot& holder);

}  // namespace ubersim::timeshim
