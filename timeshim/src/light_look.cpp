// Deterministic mode's light looks (docs/timeshim.md, "Deterministic mode"):
// after a turn, a look reads only the threads the turn can have changed.
//
// Between turns nobody runs the program's code but the thread that had the
// turn. A thread that waits for its turn, for a peer (DetBlocked) or in a
// shim sleep sleeps on a futex of the segment that only the controller or
// the shim wakes (and says so in the segment), or a signal, or its process's
// end. So after a turn that sent no signal, created no thread or process
// (the host's last pid is unchanged) and did not end, a look need not read
// those threads, nor list threads and children again: it reads the turn's
// thread and every thread that waits in the kernel (for input, which anyone
// may send), and takes the rest from the segment. Anything else, and every
// kFullLookAtLeastEvery, is a full look (quiescence.cpp).
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

// A wait only the controller, the token holder or a signal can end.
bool ends_without_input(ThreadState state) {
  return ends_only_in_turn(state) || state == ThreadState::Sleeping;
}

// What a full look would take from the slot of such a thread.
void judge_unread(const SlotView& slot, std::int64_t now, bool* owed_wake,
                  std::int64_t* next_deadline) {
  if (slot.state == ThreadState::WantToken) return;
  if (slot.deadline_ns <= now) {
    *owed_wake = true;
  } else {
    *next_deadline = std::min(*next_deadline, slot.deadline_ns);
  }
}

}  // namespace

bool Controller::turn_goes_on(const std::optional<std::pair<pid_t, pid_t>>& running) {
  return options_.deterministic && running && header().token_tid.load() == running->second;
}

bool Controller::turn_ended_settled(const std::optional<std::pair<pid_t, pid_t>>& running) {
  if (!options_.deterministic || !running || header().token_tid.load() != 0) return false;
  for (auto& slot : used_slots(header())) {
    if (slot.claim.load() == 0 || slot.tid.load() != running->second) continue;
    const auto state = static_cast<ThreadState>(slot.state.load());
    if (state != ThreadState::Timer) return ends_without_input(state);
  }
  return false;
}

void Controller::remember_full_look(const Scan& look) {
  light_.threads = look.threads;
  ++light_.full_looks;
}

std::optional<Controller::Scan> Controller::light_scan() {
  // One light look per turn: after one that was not quiet, looks are full.
  if (!std::exchange(light_.allowed, false) || !light_.holder) return std::nullopt;
  Header& segment = header();
  if (segment.signals_sent.load() != light_.signals_sent ||
      std::chrono::steady_clock::now() - light_.full_at > kFullLookAtLeastEvery) {
    return std::nullopt;
  }
  const auto last_pid = proc_->last_pid();
  if (!last_pid || last_pid != light_.last_pid) return std::nullopt;
  const pid_t holder = light_.holder->second;
  const Slots slots = slots_by_tid(segment);
  const std::int64_t now = segment.sim_now_ns.load();
  Scan result;
  result.light = true;
  std::set<pid_t> processes;
  bool holder_known = false;
  for (const auto& [pid, tid] : light_.threads) {
    processes.insert(pid);
    result.threads.emplace_back(pid, tid);
    const auto found = slots.find(tid);
    const SlotView* slot = found != slots.end() ? &found->second : nullptr;
    holder_known = holder_known || tid == holder;
    // The turn's thread too: it sleeps, or runs only the shim's code now.
    if (slot != nullptr && ends_without_input(slot->state)) {
      judge_unread(*slot, now, &result.owed_wake, &result.next_deadline);
      continue;
    }
    const auto state = proc_->state_of(pid, tid);
    if (!state || *state == 'Z' || *state == 'X') return std::nullopt;  // it ends
    judge_thread(ThreadSample{pid, tid, *state, 0}, slot, now, result);
  }
  if (!holder_known) return std::nullopt;  // a thread the last full look did not see
  result.any_process = true;
  scan_timers(segment, processes, now, &result.owed_wake, &result.next_deadline);
  if (result.owed_wake) result.all_waiting = false;
  ++light_.light_looks;
  return result;
}

}  // namespace ubersim::timeshim
