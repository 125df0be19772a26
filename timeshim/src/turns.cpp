// Deterministic mode's turns (docs/timeshim.md, "Deterministic mode"): at a
// quiescent look, every thread that wants to run has said so (WantToken) and
// every other waits; the controller gives the run token to one of them, in
// an order that depends only on what the group did: first come (by the look
// at which it was first seen wanting), then its place in the group (the
// order threads and processes were created in), never the kernel's tid.
#include <algorithm>
#include <string>
#include <vector>

#include "proc_files.hpp"
#include "proc_scan.hpp"
#include "ubersim/timeshim/controller.hpp"

namespace ubersim::timeshim {
namespace {

bool wants_token(const ThreadSlot& slot) {
  return slot.claim.load() != 0 && slot.tid.load() != 0 &&
         slot.state.load() == static_cast<std::uint32_t>(ThreadState::WantToken);
}

// Whether the thread is gone or ends (a zombie, or dead and not yet reaped).
bool ending(pid_t pid, pid_t tid, ProcFiles& proc) {
  const auto state = proc.state_of(pid, tid);
  return !state || *state == 'Z' || *state == 'X';
}

// The slot of the thread holding the token, or nullptr when it is gone.
ThreadSlot* holder_slot(Header& header, ProcFiles& proc, pid_t holder) {
  for (auto& slot : used_slots(header)) {
    if (slot.claim.load() == 0 || slot.tid.load() != holder) continue;
    if (slot.state.load() == static_cast<std::uint32_t>(ThreadState::Timer)) continue;
    // A process that ended holding it is a zombie until its parent reaps it.
    return ending(slot.pid.load(), holder, proc) ? nullptr : &slot;
  }
  return nullptr;
}

}  // namespace

std::uint64_t Controller::turns() const {
  return const_cast<Controller*>(this)->header().turns.load();
}

std::uint64_t Controller::handoffs() const {
  return const_cast<Controller*>(this)->header().handoffs.load();
}

void Controller::adopt_handed_over_turn(std::optional<std::pair<pid_t, pid_t>>& running) {
  Header& segment = header();
  const std::uint64_t handoffs = segment.handoffs.load();
  if (!options_.deterministic || handoffs == light_.handoffs_seen) return;
  light_.handoffs_seen = handoffs;
  const pid_t tid = segment.handoff_tid.load();
  for (auto& slot : used_slots(segment)) {
    if (slot.claim.load() == 0 || slot.tid.load() != tid) continue;
    const pid_t pid = slot.pid.load();
    // As after give_turn: each turn in between left what a look relies on
    // as it was (the shim checked), so the light looks go on from this one.
    proc_->forget_children(pid);
    running = std::make_pair(pid, tid);
    after_turn_given(*running);
    return;
  }
  running.reset();  // gone already: a full look tells what is left
  want_full_look();
}

std::optional<std::pair<pid_t, pid_t>> Controller::give_turn() {
  Header& segment = header();
  std::vector<ThreadSlot*> wanting;
  for (auto& slot : used_slots(segment)) {
    if (wants_token(slot)) wanting.push_back(&slot);
  }
  if (pid_t holder = segment.token_tid.load(); holder != 0) {
    ThreadSlot* slot = holder_slot(segment, *proc_, holder);
    if (slot == nullptr) {
      // It ended holding the token (exit, exec that failed to load the shim).
      segment.token_tid.compare_exchange_strong(holder, 0);
    } else {
      // Asleep in a call that did not hand the token over: nobody else may
      // run until it returns. Waiting for input, that is right; waiting
      // for another thread of the group, it never returns.
      if (wanting.empty()) return std::nullopt;
      const pid_t pid = slot->pid.load();
      const auto call = proc_->sample_syscall(pid, holder);
      note_suspect(pid, holder,
                   "holds the deterministic mode's run token while blocked in " +
                       (call ? syscall_name(call->number) : std::string("an unknown call")) +
                       ", a call the time shim does not hand the token over in; the token is "
                       "taken from it so that the others can run (this run's interleaving is "
                       "no longer fixed from here on)");
      // Named: now the others run; it waits for a turn at its next call the
      // shim sees.
      if (!suspects_[holder].reported) return std::nullopt;
      suspects_.erase(holder);
      segment.token_tid.compare_exchange_strong(holder, 0);
    }
  }
  if (wanting.empty()) return std::nullopt;
  // Those first seen wanting now get their place in the queue, by their
  // place in the group.
  std::vector<ThreadSlot*> arrived;
  for (ThreadSlot* slot : wanting) {
    if (slot->ready_seq.load() == 0) arrived.push_back(slot);
  }
  std::sort(arrived.begin(), arrived.end(), [](const ThreadSlot* a, const ThreadSlot* b) {
    return a->order_id.load() < b->order_id.load();
  });
  for (ThreadSlot* slot : arrived) slot->ready_seq.store(next_ready_place(segment));
  ThreadSlot* next = nullptr;
  while (next == nullptr) {
    const auto first = std::min_element(wanting.begin(), wanting.end(),
                                        [](const ThreadSlot* a, const ThreadSlot* b) {
                                          return a->ready_seq.load() < b->ready_seq.load();
                                        });
    // A thread whose process ended keeps its slot until it is gone: no turn
    // for it (whether it is still there depends on the kernel's timing).
    if (ending((*first)->pid.load(), (*first)->tid.load(), *proc_)) {
      // Unnumbered, so that the shim never hands it a turn (shim/handoff.cpp).
      (*first)->ready_seq.store(0);
      wanting.erase(first);
      if (wanting.empty()) return std::nullopt;
    } else {
      next = *first;
    }
  }
  next->ready_seq.store(0);
  // It runs unread by the looks until it holds the token (quiescence.cpp):
  // what its process had as children may change.
  proc_->forget_children(next->pid.load());
  // No longer wanting: a look before it runs must not give a second turn.
  next->state.store(static_cast<std::uint32_t>(ThreadState::Running));
  segment.token_tid.store(next->tid.load());
  start_turn(segment, *next);
  return std::make_pair(static_cast<pid_t>(next->pid.load()), static_cast<pid_t>(next->tid.load()));
}

}  // namespace ubersim::timeshim
