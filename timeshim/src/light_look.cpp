// Deterministic mode's light looks (docs/timeshim.md, "Deterministic mode"):
// after a turn, a look reads only the threads the turn can have changed.
//
// Between turns nobody runs the program's code but the thread that had the
// turn. A thread that waits for its turn, for a peer (DetBlocked) or in a
// shim sleep sleeps on a futex of the segment that only the controller or
// the shim wakes (and says so in the segment), or a signal, or its process's
// end. So after a turn that sent no signal, created no thread or process
// (the host's last pid is unchanged) and did not end, a look need not read
// those threads, nor list threads and children again: it reads every thread
// that waits in the kernel (for input, which anyone may send) and the turn's
// thread unless its slot says it waits, and takes the rest from the segment.
// After a turn that output nothing to an fd it need not read the threads
// that wait for input either. The looks of a call after a quiescent return
// are light too, reading also the threads the controller woke when it
// advanced sim time. So are the looks after a light one that was not
// quiescent, until the next turn: nobody ran the program's code since. After
// a signal, a new thread or process or a thread that ended, when a thread
// waits in a call the shim does not know, and every kFullLookAtLeastEvery, a
// look is a full one (quiescence.cpp).
#include <algorithm>
#include <chrono>
#include <set>
#include <utility>

#include "look.hpp"
#include "proc_files.hpp"
#include "proc_scan.hpp"

namespace ubersim::timeshim {
namespace {

// At least one full look in this much wall time: what no turn did (a signal
// from outside the group) is seen within it.
constexpr auto kFullLookAtLeastEvery = std::chrono::milliseconds(20);

}  // namespace

bool Controller::turn_goes_on(const std::optional<std::pair<pid_t, pid_t>>& running) {
  return options_.deterministic && running && header().token_tid.load() == running->second;
}

bool Controller::turn_ended_settled(const std::optional<std::pair<pid_t, pid_t>>& running) {
  if (!options_.deterministic || !running || header().token_tid.load() != 0) return false;
  for (auto& slot : used_slots(header())) {
    if (slot.claim.load() == 0 || slot.tid.load() != running->second) continue;
    const auto state = static_cast<ThreadState>(slot.state.load());
    if (state != ThreadState::Timer) {
      return settled_after_turn(state, static_cast<ShimCall>(slot.call.load()));
    }
  }
  return false;
}

// Between a quiescent return and the next call nobody ran the program's
// code (the bridge sent input and advanced time, which woke threads that run
// only the shim's code until their turn): no thread of the group was
// created since, whatever threads of other programs (the caller's own) were.
void Controller::begin_after_quiescence() {
  light_.call_start = std::exchange(light_.quiescent, false) && options_.deterministic;
  if (light_.call_start && light_.last_pid) light_.last_pid = proc_->last_pid();
}

void Controller::remember_full_look(const Scan& look, const std::set<pid_t>& alive) {
  if (options_.deterministic) {
    light_.threads = look.threads;
    keep_only_alive(light_.writes, alive);
    keep_only_alive(light_.fd_asleep, alive);
  }
  want_full_look();  // the next light look starts from this one: a turn or a call's start
  ++light_.full_looks;
}

bool Controller::turn_made_no_fd_output() {
  // Only at the first look after a turn: a later one follows a look that
  // was not quiescent, perhaps with input on its way, and reads every
  // waiter. (At a call's start the caller sent input: every waiter is read.)
  if (!light_.holder || light_.call_start || std::exchange(light_.outputs_checked, true)) {
    return false;
  }
  const std::uint64_t outputs = header().fd_outputs.load();
  const bool no_output = std::exchange(light_.fd_outputs, outputs) == outputs;
  const auto [pid, tid] = *light_.holder;
  const auto writes = proc_->writes_of(pid, tid);
  if (!writes) return false;
  const auto [last, first_turn] = light_.writes.try_emplace(tid, *writes);
  const bool no_write = !first_turn && std::exchange(last->second, *writes) == *writes;
  return no_output && no_write;
}

void Controller::after_turn_given(std::pair<pid_t, pid_t> holder) {
  light_.holder = holder;
  light_.call_start = false;
  light_.outputs_checked = false;
  light_.woken.clear();  // the look that gave the turn read them settled
}

void Controller::allow_handoffs(const Scan& look) {
  Header& segment = header();
  // Every thread read sleeps in a shim wait (and every other was judged from
  // its slot): the shim can see from the slots what a look would find, as
  // long as its turns change nothing that makes the next look a full one.
  const bool allowed =
      options_.shim_handoffs && look.only_shim_waits && light_.full_looks > 0 && light_.last_pid;
  if (allowed) {
    segment.handoff_last_pid.store(*light_.last_pid);
    segment.handoff_signals_sent.store(light_.signals_sent);
    segment.handoff_until_ns.store(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                       (light_.full_at + kFullLookAtLeastEvery).time_since_epoch())
                                       .count());
  }
  segment.handoff_allowed.store(allowed ? 1 : 0);
}

void Controller::want_full_look() {
  light_.holder.reset();
  light_.call_start = false;
  light_.woken.clear();  // read, and settled or read again by the full look
}

std::optional<Controller::Scan> Controller::light_scan(bool quiet_turn) {
  // Every look after a turn or a quiescent return, until the next turn:
  // meanwhile nobody runs the program's code (a thread that woke runs the
  // shim's until it wants its turn), so what can have changed is known.
  const auto holder = light_.holder;
  const bool call_start = light_.call_start;
  const std::set<pid_t>& woken = light_.woken;
  Header& segment = header();
  if ((!holder && !call_start) || light_.full_looks == 0 ||
      segment.signals_sent.load() != light_.signals_sent ||
      std::chrono::steady_clock::now() - light_.full_at > kFullLookAtLeastEvery) {
    return std::nullopt;
  }
  const auto last_pid = proc_->last_pid();
  if (!last_pid || last_pid != light_.last_pid) return std::nullopt;
  const Slots slots = slots_by_tid(segment);
  const std::int64_t now = segment.sim_now_ns.load();
  Scan result;
  result.light = true;
  std::set<pid_t> processes;
  for (const auto& [pid, tid] : light_.threads) {
    processes.insert(pid);
    result.threads.emplace_back(pid, tid);
    const auto found = slots.find(tid);
    const SlotView* slot = found != slots.end() ? &found->second : nullptr;
    const bool is_holder = holder && tid == holder->second;
    // A thread that waits for input and slept with none at the last look
    // sleeps still when the turn sent nothing (quiet_turn) and nobody else ran.
    const bool unread = slot != nullptr && woken.count(tid) == 0 &&
                        (is_holder ? settled_after_turn(slot->state, slot->call)
                                   : ends_without_input(slot->state) ||
                                         (quiet_turn && waits_for_input(slot->state, slot->call) &&
                                          light_.fd_asleep.count(tid) != 0));
    if (unread) {
      if (is_holder) {
        result.unread_holder = holder;
        // It checked its fds holding the token: nothing to read then.
        if (waits_for_input(slot->state, slot->call)) light_.fd_asleep.insert(tid);
      }
      judge_unread(*slot, now, &result.owed_wake, &result.next_deadline);
      continue;
    }
    const auto state = proc_->state_of(pid, tid);
    if (!state || *state == 'Z' || *state == 'X') return std::nullopt;  // it ends
    judge_thread(ThreadSample{pid, tid, *state, 0}, slot, now, result);
  }
  result.any_process = !result.threads.empty();
  scan_timers(segment, processes, now, &result.owed_wake, &result.next_deadline);
  if (result.owed_wake) result.all_waiting = false;
  ++light_.light_looks;
  return result;
}

}  // namespace ubersim::timeshim
