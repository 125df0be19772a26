#pragma once
// What one look at a group finds (quiescence.cpp, light_look.cpp), and the
// segment's views that both kinds of look use.
#include <sys/types.h>

#include <cstdint>
#include <iterator>
#include <map>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "ubersim/timeshim/controller.hpp"

namespace ubersim::timeshim {

struct Controller::Scan {
  bool any_process = false;
  std::optional<std::pair<pid_t, pid_t>> running;  // pid, tid of a thread seen running
  bool all_waiting = true;
  bool owed_wake = false;  // a shim wait whose deadline passed still sleeps
  // Every thread read has a slot and sleeps in a shim wait (no kernel wait
  // the shim does not know): none can run the program's code unannounced.
  bool only_shim_waits = true;
  std::int64_t next_deadline = kNoDeadline;
  std::map<pid_t, std::uint64_t> run_counts;  // by tid (threads read from /proc)
  // Every live thread of the group (pid, tid), read or not.
  std::vector<std::pair<pid_t, pid_t>> threads;
  bool light = false;  // a light look (light_look.cpp): run_counts is empty
  // The turn's thread a light look did not read (its slot says it waits):
  // it may still be on its way into that wait.
  std::optional<std::pair<pid_t, pid_t>> unread_holder;
};

struct SlotView {
  ThreadState state;
  std::int64_t deadline_ns;
  ShimCall call;
};

// What the controller keeps by tid (a set of tids, or a map by tid), without
// the threads a full look did not find alive.
inline pid_t tid_of(pid_t tid) {
  return tid;
}
template <typename Value>
pid_t tid_of(const std::pair<const pid_t, Value>& entry) {
  return entry.first;
}
template <typename ByTid>
void keep_only_alive(ByTid& by_tid, const std::set<pid_t>& alive) {
  for (auto it = by_tid.begin(); it != by_tid.end();) {
    it = alive.count(tid_of(*it)) != 0 ? std::next(it) : by_tid.erase(it);
  }
}

// The claimed thread slots of the segment (not timers), by tid.
std::map<pid_t, SlotView> slots_by_tid(Header& header);
// A thread a look does not read (it waits for its turn, a peer or sim
// time), judged from its slot: the deadline it can wake at, or a wake owed.
void judge_unread(const SlotView& slot, std::int64_t now, bool* owed_wake,
                  std::int64_t* next_deadline);
// Armed timers of `processes`: deadlines the group can wake at, or, when due
// and not yet fired, a wake a process's helper still owes.
void scan_timers(Header& header, const std::set<pid_t>& processes, std::int64_t now,
                 bool* owed_wake, std::int64_t* next_deadline);

}  // namespace ubersim::timeshim
