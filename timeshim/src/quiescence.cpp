// Quiescence (docs/timeshim.md, "Quiescence"): every thread of the group
// sleeps in the kernel, in a shim wait or in a wait only another party can
// end, and none ran between two looks at all of them.
#include <signal.h>
#include <sys/prctl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <set>
#include <thread>

#include "look.hpp"
#include "proc_files.hpp"
#include "proc_scan.hpp"

namespace ubersim::timeshim {

namespace {

std::string describe_kernel_wait(pid_t pid, pid_t tid, const std::optional<SyscallSample>& call) {
  std::string text = "is blocked in ";
  text += call ? syscall_name(call->number) : std::string("an unknown call");
  const std::string wchan = wchan_of(pid, tid);
  if (!wchan.empty() && wchan != "0") text += " (kernel: " + wchan + ")";
  if (call && classify_wait(*call) == KernelWait::Timed) {
    text +=
        ", a wait with a wall-time limit that the time shim does not turn into sim time "
        "(a raw syscall, a statically linked library, or a call not intercepted yet)";
  } else {
    text += ", a wait the time shim does not know";
  }
  return text;
}

std::string describe_state(char state) {
  switch (state) {
    case 'R':
      return "keeps running without a blocking call the time shim knows (a busy loop that does not "
             "read the clock through libc?): sim time cannot advance past it";
    case 'D':
      return "is in an uninterruptible kernel wait (disk?)";
    case 'T':
    case 't':
      return "is stopped (SIGSTOP or a debugger)";
    default:
      return std::string("is in kernel state ") + state;
  }
}

void free_dead_slots(Header& header, const std::set<pid_t>& alive) {
  for (auto& slot : used_slots(header)) {
    if (slot.claim.load() == 0) continue;
    pid_t tid = slot.tid.load();
    const bool timer = slot.state.load() == static_cast<std::uint32_t>(ThreadState::Timer);
    // tid 0: a slot being claimed (a thread writes its tid after taking it).
    if (!timer && (tid == 0 || alive.count(tid) != 0)) continue;
    // A timer lives as long as its process; a thread as long as its task.
    std::string path = "/proc/" + std::to_string(slot.pid.load());
    if (!timer) path += "/task/" + std::to_string(tid);
    if (::access(path.c_str(), F_OK) == 0) continue;
    // Only if the slot still holds what was judged: a new thread may have
    // taken it meanwhile.
    if (!slot.tid.compare_exchange_strong(tid, 0)) continue;
    slot.state.store(static_cast<std::uint32_t>(ThreadState::Free));
    slot.claim.store(0);
  }
}

}  // namespace

std::map<pid_t, SlotView> slots_by_tid(Header& header) {
  std::map<pid_t, SlotView> result;
  for (auto& slot : used_slots(header)) {
    if (slot.claim.load() == 0 ||
        slot.state.load() == static_cast<std::uint32_t>(ThreadState::Timer)) {
      continue;
    }
    result[slot.tid.load()] =
        SlotView{static_cast<ThreadState>(slot.state.load()), slot.deadline_ns.load(),
                 static_cast<ShimCall>(slot.call.load())};
  }
  return result;
}

void judge_unread(const SlotView& slot, std::int64_t now, bool* owed_wake,
                  std::int64_t* next_deadline) {
  if (slot.state == ThreadState::WantToken) return;
  if (slot.deadline_ns <= now) {
    *owed_wake = true;
  } else {
    *next_deadline = std::min(*next_deadline, slot.deadline_ns);
  }
}

void scan_timers(Header& header, const std::set<pid_t>& processes, std::int64_t now,
                 bool* owed_wake, std::int64_t* next_deadline) {
  for (auto& slot : used_slots(header)) {
    if (slot.claim.load() == 0 ||
        slot.state.load() != static_cast<std::uint32_t>(ThreadState::Timer)) {
      continue;
    }
    if (processes.count(slot.pid.load()) == 0) continue;
    const std::int64_t deadline = slot.deadline_ns.load();
    if (deadline <= now) {
      *owed_wake = true;
    } else {
      *next_deadline = std::min(*next_deadline, deadline);
    }
  }
}

// Where a walk over the group starts: the processes it started, and every
// process that holds a slot (a shimmed process its parent left, for one).
std::vector<pid_t> Controller::group_roots() {
  std::vector<pid_t> pending;
  for (pid_t root : roots_) {
    if (exit_status_.count(root) == 0) pending.push_back(root);
  }
  for (auto& slot : used_slots(header())) {
    if (slot.claim.load() != 0) pending.push_back(slot.pid.load());
  }
  return pending;
}

void Controller::note_suspect(pid_t pid, pid_t tid, const std::string& why) {
  const auto now = std::chrono::steady_clock::now();
  Suspect& suspect = suspects_[tid];
  if (suspect.why != why) suspect = Suspect{why, now, false};
  if (suspect.reported || now - suspect.since < options_.grace) return;
  suspect.reported = true;
  const auto waited = std::chrono::duration<double>(now - suspect.since).count();
  char seconds[32];
  std::snprintf(seconds, sizeof(seconds), "%.1f", waited);
  problems_.push_back(Problem{pid, tid,
                              "process " + std::to_string(pid) + " (" + comm_of(pid, pid) +
                                  ") thread " + std::to_string(tid) + " (" + comm_of(pid, tid) +
                                  ") " + why + "; for " + seconds + " s of wall time so far"});
}

void Controller::check_shim_loaded(pid_t pid) {
  const auto now = std::chrono::steady_clock::now();
  // A process found good is looked at again now and then, for an exec (its
  // new image may lack the shim); not at every look: reading its exe costs.
  constexpr auto kExeRecheck = std::chrono::milliseconds(100);
  // A new image maps the shim only once its loader has run: until then, and
  // on a loaded machine that can take a while, it shows no shim.
  constexpr auto kLoaderGrace = std::chrono::milliseconds(500);
  const auto checked = shim_checked_.find(pid);
  auto& next_look = next_exe_look_[pid];
  if (checked != shim_checked_.end() && now < next_look) return;
  next_look = now + kExeRecheck;
  const std::string exe = exe_of(pid);
  if (exe.empty() || (checked != shim_checked_.end() && checked->second == exe)) return;
  ImageSeen& image = image_seen_[pid];
  if (image.exe != exe) image = ImageSeen{exe, now};
  // A program that reads the clock without libc, shim or not (its file says so).
  if (const std::string why = clock_without_libc(exe); !why.empty()) {
    shim_checked_[pid] = exe;
    problems_.push_back(Problem{pid, 0,
                                "process " + std::to_string(pid) + " (" + comm_of(pid, pid) + ", " +
                                    exe + ") sees wall time: " + why});
    return;
  }
  if (now - image.since < kLoaderGrace) return;
  const std::string library = shim_library_.substr(shim_library_.rfind('/') + 1);
  if (maps_contain(pid, library)) {
    shim_checked_[pid] = exe;
    return;
  }
  const auto main_thread = proc_->sample_thread(pid, pid);
  if (!main_thread || main_thread->state == 'R') return;  // may still be in exec: look again
  shim_checked_[pid] = exe;
  const bool is_static = elf_is_dynamic(exe) == false;
  problems_.push_back(Problem{
      pid, 0,
      "process " + std::to_string(pid) + " (" + comm_of(pid, pid) + ", " + exe +
          ") runs without the time shim: " +
          (is_static ? "it is statically linked (no ELF interpreter), LD_PRELOAD has no effect"
                     : "the shim is not loaded (LD_PRELOAD removed from its environment?)") +
          "; it sees wall time"});
}

Controller::Scan Controller::scan() {
  reap(false);
  proc_->new_look();
  Header& segment = header();
  // Before the walk: a thread created during it changes them, and the next
  // look is full again (light_look.cpp: deterministic mode only).
  if (options_.deterministic) {
    light_.last_pid = proc_->last_pid();
    light_.signals_sent = segment.signals_sent.load();
    light_.fd_outputs = segment.fd_outputs.load();
    light_.full_at = std::chrono::steady_clock::now();
  }
  const Slots slots = slots_by_tid(segment);
  const std::int64_t now = segment.sim_now_ns.load();
  Scan result;
  std::set<pid_t> alive;
  std::set<pid_t> processes;
  std::set<pid_t> seen;
  std::vector<pid_t> pending = group_roots();
  while (!pending.empty()) {
    const pid_t pid = pending.back();
    pending.pop_back();
    if (pid <= 0 || !seen.insert(pid).second) continue;
    if (::kill(pid, 0) != 0 && errno == ESRCH) continue;
    processes.insert(pid);
    // Its threads first, then its children: run counts read before the
    // children tell whether they can have changed since (proc_files.hpp).
    const auto asleep = look_at_process(pid, slots, now, result, alive);
    for (pid_t child : proc_->children_of(pid, asleep)) pending.push_back(child);
  }
  scan_timers(segment, processes, now, &result.owed_wake, &result.next_deadline);
  if (result.owed_wake) result.all_waiting = false;
  free_dead_slots(segment, alive);
  proc_->keep_only(processes, alive);
  keep_only_alive(suspects_, alive);
  remember_full_look(result, alive);
  return result;
}

// One process's threads, judged into `result`; the run count of each when
// every one of them sleeps, else nullopt.
std::optional<RunCounts> Controller::look_at_process(pid_t pid, const Slots& slots,
                                                     std::int64_t now, Scan& result,
                                                     std::set<pid_t>& alive) {
  check_shim_loaded(pid);
  const pid_t token_holder = header().token_tid.load();
  RunCounts counts;
  bool all_sleep = true;
  // A process whose first thread does not sleep may be ending: an exit or
  // a fatal signal wakes each of its threads to die, whatever its slot says.
  const auto leader = proc_->sample_thread(pid, pid);
  const bool leader_sleeps = leader && leader->state == 'S';
  for (pid_t tid : proc_->threads_of(pid)) {
    const auto slot = slots.find(tid);
    // Not the token holder: a thread says DetBlocked before it gives the
    // token back, and runs until it has.
    if (leader_sleeps && tid != pid && tid != token_holder && slot != slots.end() &&
        ends_only_in_turn(slot->second.state)) {
      // Its turn comes from give_turn (turns.cpp), which looks at it then,
      // or from its deadline (a timed lock, condition or semaphore wait).
      result.any_process = true;
      alive.insert(tid);
      result.threads.emplace_back(pid, tid);
      counts[tid] = kNotRead;
      suspects_.erase(tid);
      // A deadline passed: wake_due makes it want the token.
      judge_unread(slot->second, now, &result.owed_wake, &result.next_deadline);
      continue;
    }
    const auto sample = tid == pid ? leader : proc_->sample_thread(pid, tid);
    if (!sample || sample->state == 'Z' || sample->state == 'X') {
      all_sleep = false;  // it ends: its children go to another thread
      result.only_shim_waits = false;
      continue;
    }
    result.any_process = true;
    alive.insert(tid);
    result.threads.emplace_back(pid, tid);
    result.run_counts[tid] = sample->run_count;
    counts[tid] = sample->run_count;
    if (sample->state != 'S') all_sleep = false;
    judge_thread(*sample, slot != slots.end() ? &slot->second : nullptr, now, result);
  }
  if (!all_sleep) return std::nullopt;
  return counts;
}

// What a thread the look read holds back: nothing (it waits for sim time, its
// turn or the group), or the group's quiescence (it runs, or waits in a way
// only wall time ends), noted as a suspect.
void Controller::judge_thread(const ThreadSample& sample, const SlotView* slot, std::int64_t now,
                              Scan& result) {
  const pid_t pid = sample.pid;
  const pid_t tid = sample.tid;
  const bool sleeps = sample.state == 'S';
  if (options_.deterministic) {
    // For the light looks after quiet turns (light_look.cpp).
    if (sleeps && slot != nullptr && slot->state == ThreadState::WaitingFd) {
      light_.fd_asleep.insert(tid);
    } else {
      light_.fd_asleep.erase(tid);
    }
  }
  // Below, only the shim's own waits return early.
  if (!sleeps || slot == nullptr) result.only_shim_waits = false;
  if (slot != nullptr && slot->state == ThreadState::Helper) {
    if (!sleeps) result.all_waiting = false;  // waking a waiter now
    return;
  }
  if (sleeps && slot != nullptr && slot->state == ThreadState::WantToken) {
    suspects_.erase(tid);  // deterministic mode: waits for its turn (turns.cpp)
    return;
  }
  if (sleeps && slot != nullptr && is_shim_wait(slot->state)) {
    if (slot->deadline_ns <= now) {
      result.owed_wake = true;
      result.all_waiting = false;
      note_suspect(pid, tid,
                   std::string("was woken at the end of its ") + shim_call_name(slot->call) +
                       " but still sleeps");
    } else {
      result.next_deadline = std::min(result.next_deadline, slot->deadline_ns);
      suspects_.erase(tid);
    }
    return;
  }
  if (!sleeps) {
    result.all_waiting = false;
    if (sample.state == 'R') result.running = {pid, tid};
    note_suspect(pid, tid, describe_state(sample.state));
    return;
  }
  // A wait outside the shim with no time limit (input, a lock, a child)
  // waits for the group or for input: it does not hold time back.
  result.only_shim_waits = false;
  const auto call = proc_->sample_syscall(pid, tid);
  if (call && classify_wait(*call) == KernelWait::ForOthers) {
    // The token holder's suspicion is give_turn's (turns.cpp).
    if (tid != header().token_tid.load()) suspects_.erase(tid);
    return;
  }
  result.all_waiting = false;
  note_suspect(pid, tid, describe_kernel_wait(pid, tid, call));
}

// The thread a look saw running runs still: no need to look at all of them.
// (Looks are the controller's cost: a team program that computes would
// otherwise be looked at every few tens of microseconds.)
bool Controller::still_running(std::optional<std::pair<pid_t, pid_t>>& running) {
  if (!running) return false;
  const auto [pid, tid] = *running;
  if (proc_->state_of(pid, tid) == 'R') {
    note_suspect(pid, tid, describe_state('R'));
    return true;
  }
  running.reset();
  return false;
}

// Nobody ran between two looks (same run counts, no shim call): at an instant
// between them every thread slept.
bool Controller::quiet_at_one_instant(const Scan& look, std::uint32_t seq, bool between_turns) {
  if (between_turns && look.only_shim_waits) {
    // Deterministic mode, no turn running, every thread in a shim wait: one
    // look is enough. Without the token nobody runs the program's code, so
    // nobody wakes anybody; a thread that input (or its process's timer
    // helper) woke says so in the segment (change_seq) before it runs any,
    // or the look saw it running. (A thread that still holds the token is
    // read, never skipped, so that "no holder" is what the look saw.)
    return header().change_seq.load() == seq && header().token_tid.load() == 0;
  }
  if (look.light) return false;  // no run counts: full looks decide
  const Scan second = scan();
  return second.all_waiting && second.run_counts == look.run_counts &&
         header().change_seq.load() == seq;
}

namespace {

// The looks' short waits (tens of microseconds) as asked: the kernel's
// default slack (50 us) would more than double them, and a turn in
// deterministic mode waits for one or two of them.
void tighten_timer_slack() {
  static thread_local bool tightened = false;
  if (!tightened) ::prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
  tightened = true;
}

}  // namespace

Quiescence Controller::wait_quiescent(std::chrono::milliseconds wall_limit) {
  tighten_timer_slack();
  Header& segment = header();
  const auto give_up = std::chrono::steady_clock::now() + wall_limit;
  constexpr long kFirstBackoffNs = 20000;
  constexpr long kLongestBackoffNs = 5000000;
  // Deterministic mode: how long the controller first waits for a turn to
  // end before it reads the thread (its end is said in the segment; the
  // read is for a thread that blocks or ends holding the token).
  constexpr long kFirstTurnWaitNs = 500000;
  long backoff_ns = kFirstBackoffNs;
  long turn_wait_ns = kFirstTurnWaitNs;
  begin_after_quiescence();
  std::optional<std::pair<pid_t, pid_t>> running;
  for (;;) {
    const std::uint32_t seq = segment.change_seq.load();
    adopt_handed_over_turn(running);
    if (turn_goes_on(running)) {
      if (std::chrono::steady_clock::now() >= give_up)
        return Quiescence{GroupState::Busy, kNoDeadline};
      if (futex_wait(segment.change_seq, seq, turn_wait_ns) == 0 ||
          segment.change_seq.load() != seq) {
        continue;
      }
      // The shim handed the turn on (and does not wake the controller for it).
      if (segment.handoffs.load() != light_.handoffs_seen) continue;
      turn_wait_ns = std::min(turn_wait_ns * 2, kLongestBackoffNs);
      if (still_running(running)) continue;
      // It sleeps holding the token, or ended: a full look (and give_turn) tells.
    }
    if (turn_ended_settled(running)) running.reset();
    // A full look at least every kLongestBackoffNs (owed wakes, new threads).
    if (backoff_ns < kLongestBackoffNs && still_running(running)) {
      if (std::chrono::steady_clock::now() >= give_up)
        return Quiescence{GroupState::Busy, kNoDeadline};
      backoff_ns = futex_wait(segment.change_seq, seq, backoff_ns) == 0
                       ? kFirstBackoffNs
                       : std::min(backoff_ns * 2, kLongestBackoffNs);
      continue;
    }
    const bool between_turns = options_.deterministic && segment.token_tid.load() == 0;
    // Input on its way through the kernel before the look (proc_files.hpp)
    // wakes its receiver after the look read it: not quiet until it arrived
    // (deterministic mode, where the order of turns depends on it; the two
    // reads would slow the other mode's looks by about a third).
    // After a turn that sent nothing nothing of the group's is on its way
    // (the looks before checked), and the threads that wait for input need
    // not be read (light_look.cpp).
    const bool quiet_turn = between_turns && turn_made_no_fd_output();
    const bool input_in_flight =
        options_.deterministic && !quiet_turn && proc_->softirq_work_pending();
    std::optional<Scan> light = between_turns ? light_scan(quiet_turn) : std::nullopt;
    const Scan look = light ? std::move(*light) : scan();
    running = look.running;
    if (!look.any_process) {
      reap(true);  // what is left of the group are zombies
      return Quiescence{GroupState::Exited, kNoDeadline};
    }
    if (look.owed_wake) wake_due();
    // A thread in a wait the shim does not know: two full looks tell.
    if (look.light && look.all_waiting && !look.only_shim_waits) {
      want_full_look();
      continue;
    }
    if (look.all_waiting && !input_in_flight && quiet_at_one_instant(look, seq, between_turns)) {
      // Deterministic mode: quiescent only when nobody wants to run.
      if (options_.deterministic) {
        allow_handoffs(look);
        if (auto holder = give_turn()) {
          running = holder;  // it runs now: looked at alone until it stops
          after_turn_given(*holder);
          backoff_ns = kFirstBackoffNs;
          turn_wait_ns = kFirstTurnWaitNs;
          continue;
        }
      }
      // Quiescent for the caller: every thread sleeps, the turn's thread a
      // light look did not read too (it may still be on its way into its wait).
      if (!look.unread_holder ||
          proc_->state_of(look.unread_holder->first, look.unread_holder->second) == 'S') {
        light_.quiescent = true;
        want_full_look();  // until the next call: begin_after_quiescence
        return Quiescence{GroupState::Quiescent, look.next_deadline};
      }
    }
    if (std::chrono::steady_clock::now() >= give_up)
      return Quiescence{GroupState::Busy, kNoDeadline};
    if (futex_wait(segment.change_seq, seq, backoff_ns) == 0 || segment.change_seq.load() != seq) {
      backoff_ns = kFirstBackoffNs;
    } else {
      backoff_ns = std::min(backoff_ns * 2, kLongestBackoffNs);
    }
  }
}

}  // namespace ubersim::timeshim
