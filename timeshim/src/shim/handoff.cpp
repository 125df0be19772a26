// Deterministic mode's turns handed over by the shim (docs/timeshim.md,
// "Turns without a look"). After a turn, the controller looks at the group
// and gives the token to the thread that has waited longest (turns.cpp). When
// the turn output nothing to an fd, wrote nothing, sent no signal and created
// no thread or process, that look can only find what the last one found, but
// for the turn's own thread: so the thread ending its turn gives the token to
// the next one itself, by the same rule, and the controller (which sleeps
// meanwhile) takes up the count when it next wakes. One wake-up fewer per
// turn, on a machine where each costs a wait for a core.
#include "handoff.hpp"

#include <fcntl.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <optional>

#include "runtime.hpp"

namespace ubersim::timeshim::shim {
namespace {

struct TurnRecord {
  std::uint64_t fd_outputs_at_start;  // the group's counted fd outputs when the turn began
  std::uint64_t writes_seen;          // the thread's write calls when last read
  bool writes_known;                  // ... at the end of its last turn: so at this one's start
};

__attribute__((tls_model("initial-exec"))) thread_local TurnRecord this_turn{};

// A small /proc file, NUL-terminated in `text`, read with raw system calls:
// the shim's own read and close are interposed (and its close counts as an
// fd output). No allocation: this runs inside the program's calls.
struct ProcText {
  char text[512];
};

bool read_proc_file(const char* path, ProcText& into) {
  const long fd = ::syscall(SYS_openat, AT_FDCWD, path, O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  const long got = ::syscall(SYS_read, fd, into.text, sizeof(into.text) - 1);
  ::syscall(SYS_close, fd);
  if (got <= 0) return false;
  into.text[got] = '\0';
  return true;
}

std::optional<std::uint64_t> number_at(const char* at) {
  if (at == nullptr) return std::nullopt;
  char* end = nullptr;
  const unsigned long long value = std::strtoull(at, &end, 10);
  if (end == at) return std::nullopt;
  return value;
}

// This thread's write calls as the kernel counts them (syscw): also the
// ones libc makes inside (stdio), which no interposer sees.
std::optional<std::uint64_t> own_writes() {
  ProcText io{};
  if (!read_proc_file("/proc/thread-self/io", io)) return std::nullopt;
  const char* key = std::strstr(io.text, "syscw: ");
  return number_at(key == nullptr ? nullptr : key + 7);
}

// The host's last pid (the last field of /proc/loadavg): a new thread or
// process anywhere changes it, one of the group made by any means too.
std::optional<std::uint64_t> host_last_pid() {
  ProcText loadavg{};
  if (!read_proc_file("/proc/loadavg", loadavg)) return std::nullopt;
  const char* space = std::strrchr(loadavg.text, ' ');
  return number_at(space == nullptr ? nullptr : space + 1);
}

bool waits_past(const ThreadSlot& slot, std::int64_t now) {
  return slot.deadline_ns.load() > now;
}

// The state the turn's thread ended in, as the look after it would judge it
// without reading the thread (settled_after_turn, shared_state.hpp): waiting
// for its turn, a peer, sim time or input that was not there when it looked.
// The hand-over also needs what the look finds out itself: a thread that
// wants the token has no place in the queue yet (the look would number it),
// and a deadline is not yet reached.
bool settled(const ThreadSlot& own, std::int64_t now) {
  const auto state = static_cast<ThreadState>(own.state.load());
  if (!settled_after_turn(state, static_cast<ShimCall>(own.call.load()))) return false;
  return state == ThreadState::WantToken ? own.ready_seq.load() == 0 : waits_past(own, now);
}

// The thread the controller's look would give the turn to: the one that
// wants it and has waited longest. nullptr when the look could find more
// than the last one did: a thread that wants the token and has no place in
// the queue yet (the look would number it, with any others, by their place
// in the group), a deadline reached, a thread between states.
ThreadSlot* next_in_queue(Header& segment, const ThreadSlot& own, std::int64_t now) {
  ThreadSlot* next = nullptr;
  for (auto& slot : used_slots(segment)) {
    if (&slot == &own || slot.claim.load() == 0) continue;
    if (slot.tid.load() == 0) return nullptr;  // being claimed
    switch (static_cast<ThreadState>(slot.state.load())) {
      case ThreadState::WantToken: {
        const std::uint64_t place = slot.ready_seq.load();
        if (place == 0) return nullptr;
        if (next == nullptr || place < next->ready_seq.load()) next = &slot;
        break;
      }
      case ThreadState::Helper:
        break;  // woken only by the controller
      case ThreadState::Timer:
      case ThreadState::DetBlocked:
      case ThreadState::Sleeping:
      case ThreadState::WaitingFd:
        if (!waits_past(slot, now)) return nullptr;
        break;
      default:
        return nullptr;
    }
  }
  return next;
}

// Whether the turn left everything a look relies on as it was: no fd output
// or write of its thread, no signal, no new thread or process, and the
// controller's last full look recent enough.
bool turn_was_quiet(Header& segment) {
  const auto writes = own_writes();
  const bool wrote = !writes || !this_turn.writes_known || *writes != this_turn.writes_seen;
  this_turn.writes_known = writes.has_value();
  if (writes) this_turn.writes_seen = *writes;
  if (wrote || segment.fd_outputs.load() != this_turn.fd_outputs_at_start ||
      segment.signals_sent.load() != segment.handoff_signals_sent.load() ||
      wall_monotonic_ns() >= segment.handoff_until_ns.load()) {
    return false;
  }
  const auto last_pid = host_last_pid();
  return last_pid && static_cast<std::int64_t>(*last_pid) == segment.handoff_last_pid.load();
}

}  // namespace

void note_turn_start(Header& segment) {
  this_turn.fd_outputs_at_start = segment.fd_outputs.load();
}

void forget_turn_writes() {
  this_turn.writes_known = false;
}

bool hand_off_turn(Header& segment, ThreadSlot& own, pid_t own_tid) {
  if (segment.handoff_allowed.load() == 0) {
    forget_turn_writes();
    return false;
  }
  if (!turn_was_quiet(segment)) return false;
  const std::int64_t now = segment.sim_now_ns.load();
  if (!settled(own, now)) return false;
  ThreadSlot* next = next_in_queue(segment, own, now);
  if (next == nullptr) return false;
  // The look would number this thread now, the only one new to the queue.
  if (own.state.load() == static_cast<std::uint32_t>(ThreadState::WantToken)) {
    own.ready_seq.store(next_ready_place(segment));
  }
  const std::uint64_t place = next->ready_seq.load();
  const pid_t next_tid = next->tid.load();
  // As give_turn: no longer wanting before it holds the token (it may run at
  // once, and what it then says of itself must not be overwritten).
  next->ready_seq.store(0);
  next->state.store(static_cast<std::uint32_t>(ThreadState::Running));
  segment.handoff_tid.store(next_tid);
  std::int32_t holder = own_tid;
  if (!segment.token_tid.compare_exchange_strong(holder, next_tid)) {
    // The controller took the token from this thread (it thought it blocked
    // holding it): the next one waits for the controller's turn.
    auto running = static_cast<std::uint32_t>(ThreadState::Running);
    next->state.compare_exchange_strong(running,
                                        static_cast<std::uint32_t>(ThreadState::WantToken));
    next->ready_seq.store(place);
    return false;
  }
  segment.handoffs.fetch_add(1);
  start_turn(segment, *next);
  return true;
}

}  // namespace ubersim::timeshim::shim
