#pragma once
// The time shim's controller (docs/timeshim.md): owns simulation time for a
// group of processes started under the shim (libubersim_timeshim.so), knows
// every thread of the group, detects quiescence (every thread waits: for a
// sim-time deadline, or for input), and advances sim time when told to.
//
//   Controller group(ControllerOptions{});
//   group.spawn({"python3", "team.py"});
//   for (;;) {  // as fast as the group allows: to each next deadline
//     const Quiescence q = group.run_until(kNoDeadline, std::chrono::seconds(1));
//     if (q.state == GroupState::Exited) break;
//   }
//
// A simulation drives it with run_until(T): "advance to T"; the call returns
// once the group is quiescent at T, that is once everything it will send up
// to sim time T has been sent.
#include <sys/types.h>

#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "ubersim/timeshim/shared_state.hpp"

namespace ubersim::timeshim {

class ProcFiles;
struct ThreadSample;
struct SlotView;  // what a thread's slot says, as a look reads it (quiescence.cpp)

struct ControllerOptions {
  // The shim library; "" finds it next to the running program (../lib).
  std::string shim_library;
  // Folder of the shared segment's file; "" uses $TMPDIR, else /dev/shm, else /tmp.
  std::string segment_dir;
  // CLOCK_REALTIME at sim time 0 (ns since 1970); the default is fixed so that
  // runs are alike: 2026-01-01T00:00:00Z.
  std::int64_t realtime_epoch_ns = 1767225600LL * 1000000000LL;
  // Sim time charged per intercepted call that does not block (after the
  // first 100 since the thread last blocked), and how far a thread's charge
  // may run ahead of sim time before it pauses.
  std::int64_t charge_ns = 1000;
  std::int64_t yield_after_ns = 1000000;
  // Wall time a thread may stay in a state that holds the group back (running
  // without blocking, blocked in a call the shim does not know) before it is
  // reported by name.
  std::chrono::milliseconds grace{2000};
  // Deterministic mode (docs/timeshim.md): the group's threads run one at a
  // time, each until it blocks, in a fixed order, so that what they do
  // interleaves alike on every run.
  bool deterministic = false;
  // Deterministic mode: the shim hands a turn that changed nothing a look
  // relies on to the next thread itself (docs/timeshim.md, "Turns without a
  // look"). Off: a look after every turn, the same interleaving (for tests
  // and the benchmark).
  bool shim_handoffs = true;
};

// Something the controller found that keeps the shim from working: named,
// never silent. `pid`/`tid` are 0 when not about one thread.
struct Problem {
  pid_t pid = 0;
  pid_t tid = 0;
  std::string text;
};

// A program that cannot run under the shim (statically linked).
class UnsupportedProgram : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class GroupState {
  Quiescent,  // every thread waits; next_deadline_ns is the earliest sim deadline
  Busy,       // the wall-time limit passed before the group was quiescent
  Exited,     // no process of the group is left
};

struct Quiescence {
  GroupState state = GroupState::Busy;
  std::int64_t next_deadline_ns = kNoDeadline;  // kNoDeadline: only input can wake it
};

class Controller {
 public:
  explicit Controller(ControllerOptions options);
  ~Controller();
  Controller(const Controller&) = delete;
  Controller& operator=(const Controller&) = delete;

  // Starts argv (argv[0] searched in PATH) under the shim, with stdout and
  // stderr to `output_path` ("" inherits the controller's). Throws
  // UnsupportedProgram for a statically linked program.
  pid_t spawn(const std::vector<std::string>& argv, const std::string& output_path = "");
  // What a process needs in its environment to join the group (LD_PRELOAD,
  // UBERSIM_TIMESHIM_SHM), for programs started by other means.
  std::vector<std::string> environment() const;

  std::int64_t now_ns() const;
  // Waits (up to wall_limit) until the group is quiescent or gone.
  Quiescence wait_quiescent(std::chrono::milliseconds wall_limit);
  // Sets sim time to sim_ns (not before now) and wakes the threads whose
  // deadline it reached. Call it when the group is quiescent.
  void advance_to(std::int64_t sim_ns);
  // Runs the group's own deadlines up to until_ns: while quiescent, advances
  // to the next deadline not after until_ns; returns quiescent at until_ns
  // (now_ns() == until_ns unless until_ns is kNoDeadline), Exited, or Busy
  // when wall_limit passed first.
  Quiescence run_until(std::int64_t until_ns, std::chrono::milliseconds wall_limit);

  // Problems found since the last call (each reported once).
  std::vector<Problem> take_problems();
  // Exit status of a spawned process once it ended (0..255, 128 + signal).
  std::optional<int> exit_status(pid_t pid) const;
  std::uint64_t intercepted_calls() const;
  // How often a thread that polled without blocking paused (its charge
  // reached yield_after_ns): about yield_after_ns apart per such thread.
  std::uint64_t charged_pauses() const;
  std::uint64_t advances() const { return advances_; }
  // Deterministic mode: turns granted so far.
  std::uint64_t turns() const;
  // Of those, the turns the shim handed from one thread to the next itself
  // (shim/handoff.cpp), with no look between them.
  std::uint64_t handoffs() const;
  // Looks at the group so far: full ones (every thread read) and light ones
  // (deterministic mode, after a turn: only what the turn can have changed).
  std::uint64_t full_looks() const { return light_.full_looks; }
  std::uint64_t light_looks() const { return light_.light_looks; }

 private:
  struct Scan;
  Scan scan();  // one look at every thread of the group
  // Deterministic mode, after a turn: a light look (light_look.cpp), or
  // nullopt when what the turn did needs a full one.
  std::optional<Scan> light_scan(bool quiet_turn);
  // Deterministic mode, before the look after a turn (light_look.cpp):
  // whether the turn made no call that can end another thread's wait for an
  // fd (no write the kernel counted for its thread, no send, connect,
  // shutdown or close the shim counted) since the last look.
  bool turn_made_no_fd_output();
  // What the light looks start from: a turn given to `holder`; or nothing
  // (the next look is a full one, unless a call starts after a quiescent return).
  void after_turn_given(std::pair<pid_t, pid_t> holder);
  void want_full_look();
  // `alive`: the tids of the look's threads (Scan::threads), as the look collected them.
  void remember_full_look(const Scan& look, const std::set<pid_t>& alive);
  void begin_after_quiescence();
  // Deterministic mode (light_look.cpp): the thread given the turn holds the
  // token still; or it gave it back and its slot says it waits for its turn,
  // a peer or sim time (what it still runs is the shim's, not the program's).
  bool turn_goes_on(const std::optional<std::pair<pid_t, pid_t>>& running);
  bool turn_ended_settled(const std::optional<std::pair<pid_t, pid_t>>& running);
  // Deterministic mode (light_look.cpp, turns.cpp): before a turn is given after `look`,
  // whether the shim may hand the turns after it over itself, and what they
  // must leave as it is; after, takes up the turns the shim handed over
  // since (the thread holding the token now, or the last to get it), as if
  // given here.
  void allow_handoffs(const Scan& look);
  void adopt_handed_over_turn(std::optional<std::pair<pid_t, pid_t>>& running);
  using Slots = std::map<pid_t, SlotView>;  // by tid
  std::vector<pid_t> group_roots();
  std::optional<std::map<pid_t, std::uint64_t>> look_at_process(pid_t pid, const Slots& slots,
                                                                std::int64_t now, Scan& result,
                                                                std::set<pid_t>& alive);
  void judge_thread(const ThreadSample& sample, const SlotView* slot, std::int64_t now,
                    Scan& result);
  bool quiet_at_one_instant(const Scan& look, std::uint32_t seq, bool between_turns);
  bool still_running(std::optional<std::pair<pid_t, pid_t>>& running);
  void reap(bool wait_for_end);
  void wake_due();
  void note_suspect(pid_t pid, pid_t tid, const std::string& why);
  void check_shim_loaded(pid_t pid);
  // Deterministic mode, at a quiescent look (turns.cpp): the pid and tid of
  // the thread given the run token, or nullopt when nobody wants it.
  std::optional<std::pair<pid_t, pid_t>> give_turn();
  Header& header();

  class Segment;
  ControllerOptions options_;
  std::unique_ptr<Segment> segment_;
  std::unique_ptr<ProcFiles> proc_;  // the /proc files every look reads, kept open
  std::string shim_library_;
  std::vector<pid_t> roots_;
  std::map<pid_t, int> exit_status_;
  struct Suspect {
    std::string why;
    std::chrono::steady_clock::time_point since;
    bool reported = false;
  };
  std::map<pid_t, Suspect> suspects_;          // by tid
  std::map<pid_t, std::string> shim_checked_;  // pid -> exe it was checked for
  struct ImageSeen {
    std::string exe;                              // the program a process runs
    std::chrono::steady_clock::time_point since;  // since when (its exec, as first seen)
  };
  std::map<pid_t, ImageSeen> image_seen_;
  std::map<pid_t, std::chrono::steady_clock::time_point> next_exe_look_;
  std::vector<Problem> problems_;
  std::uint64_t advances_ = 0;
  // What a light look relies on (light_look.cpp).
  struct LightLooks {
    // The thread of the turn given last, until the look after it.
    std::optional<std::pair<pid_t, pid_t>> holder;
    // The group was quiescent when wait_quiescent returned last; its next
    // call's first look may be light.
    bool quiescent = false;
    bool call_start = false;
    std::set<pid_t> woken;  // threads wake_due woke since the last look
    // At the last full look: the group's threads, the host's last pid, the
    // group's signals sent, and when.
    std::vector<std::pair<pid_t, pid_t>> threads;
    std::optional<long> last_pid;
    std::uint64_t signals_sent = 0;
    std::chrono::steady_clock::time_point full_at;
    std::uint64_t full_looks = 0;
    std::uint64_t light_looks = 0;
    // Threads that wait for fds and were, when last read or at the end of
    // their turn, asleep with nothing to read: until a turn outputs to an fd
    // (or input comes from outside the group), they still sleep.
    std::set<pid_t> fd_asleep;
    std::uint64_t fd_outputs = 0;           // the group's counted fd outputs at the last look
    bool outputs_checked = false;           // the look after the turn asked whether it output
    std::map<pid_t, std::uint64_t> writes;  // by tid: its write calls after its last turn
    std::uint64_t handoffs_seen = 0;        // the shim's hand-overs taken up so far
  } light_;
};

// The shim library next to the running program: <dir of /proc/self/exe>/../lib.
std::string default_shim_library();

}  // namespace ubersim::timeshim
