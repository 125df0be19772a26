#pragma once
// Team programs under the time shim, hosted by the SSL bridge (docs/timeshim.md,
// "Integration with sync mode"): the bridge starts each team's command under
// a timeshim::Controller of its own (each command its own group; all on one
// sim clock, advanced together) and runs them step by step, so that
// everything a team sends is stamped with the sim time at which it was sent
// and everything the bridge sends reaches the team at the sim time it stands
// for. A group per command, not one for all: the teams' programs share
// nothing but the bridge, so their controllers look at them side by side, and
// in deterministic mode each program has a run token of its own (one token
// for both ran the two teams one thread at a time on any number of cores).
//
// run_to(T) is the one loop: wait until every thread of every group waits
// (quiescence: whatever the teams sent is in the bridge's sockets now), let the
// bridge drain and answer (at_quiescence; when it sent something to the group,
// the group runs again at the same instant), promise "nothing is sent before
// min(next deadline, T)", and advance sim time there.
#include <sys/types.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "ubersim/channels.hpp"
#include "ubersim/timeshim/controller.hpp"

namespace ubersim::ssl {

// What a team program speaks (--team-protocol): the SSL protocols (vision
// multicast in, RobotControl out), ubersim's LCM contract on a private bus
// (lcm_team_door.hpp), or grSim's (vision multicast in, grSim_Packet out).
enum class TeamProtocol { Ssl, Lcm, Grsim };

struct TeamCommand {
  Team team = Team::Yellow;
  bool both = false;    // one program plays both colours (team is then Yellow)
  std::string command;  // run as /bin/sh -c COMMAND
  TeamProtocol protocol = TeamProtocol::Ssl;

  std::string colour() const { return both ? "both" : team_name(team); }
};

struct TeamGroupOptions {
  std::vector<TeamCommand> commands;
  std::string output_dir;  // each team's output in team_<colour>.log there; "": the bridge's own
  timeshim::ControllerOptions controller;
};

class TeamGroup {
 public:
  // Returns true when it sent something to the group (run it again first).
  using AtQuiescence = std::function<bool(std::int64_t now_ns)>;
  // Nothing the group sends is stamped before promise_ns.
  using Promise = std::function<void(std::int64_t promise_ns)>;
  using ShouldStop = std::function<bool()>;

  explicit TeamGroup(TeamGroupOptions options);
  ~TeamGroup();
  TeamGroup(const TeamGroup&) = delete;
  TeamGroup& operator=(const TeamGroup&) = delete;

  // Starts every command (throws timeshim::UnsupportedProgram for a static one).
  void start();
  // Runs the group up to until_ns (see above). False when the group has ended
  // (every process of it exited) or should_stop said so.
  bool run_to(std::int64_t until_ns, const AtQuiescence& at_quiescence, const Promise& promise,
              const ShouldStop& should_stop);
  std::int64_t now_ns() const;
  bool exited() const { return exited_; }
  // Asks every command to end (SIGTERM); the destructor kills what is left.
  void stop();
  std::uint64_t quiescences() const { return quiescences_; }
  std::uint64_t advances() const;
  std::uint64_t turns() const;     // deterministic mode's turns, of every group
  std::uint64_t handoffs() const;  // of those, the ones the shim handed over itself
  // Pauses of threads that polled without blocking, of every group
  // (timeshim::Controller::charged_pauses).
  std::uint64_t charged_pauses() const;
  // The controllers' looks at their groups, full and light, of every group
  // (timeshim::Controller::full_looks).
  std::uint64_t full_looks() const;
  std::uint64_t light_looks() const;
  // Which command's program sent from this local UDP port (the order of the
  // commands), or the number of commands when none did: what orders their
  // held commands (held_for_next_frame.hpp). Looked up once per port.
  std::size_t program_of_port(std::uint16_t port);

 private:
  // The sum of what `count` says of each group's controller.
  std::uint64_t sum_over_groups(std::uint64_t (timeshim::Controller::*count)() const) const;
  void report_problems();
  void report_exits(const char* when);
  // Once per command, while the game runs slower than real time because its
  // threads poll: which options trade that polling for speed.
  void hint_at_polling();
  // The CPU time each command's processes and the bridge used, per game second.
  void report_cpu() const;
  // Waits (up to wall_limit) until every group is quiescent; Exited once
  // every group has ended; the earliest next deadline of them all.
  timeshim::Quiescence wait_quiescent(std::chrono::milliseconds wall_limit);
  void advance_to(std::int64_t sim_ns);

  TeamGroupOptions options_;
  std::vector<std::unique_ptr<timeshim::Controller>> controllers_;  // one per command
  std::vector<bool> group_ended_;                                   // per command
  std::map<std::uint16_t, std::size_t> programs_by_port_;           // program_of_port
  std::vector<pid_t> pids_;
  std::vector<bool> exit_reported_;   // per command: its end was logged
  std::vector<bool> polling_hinted_;  // per command: hint_at_polling said it
  std::chrono::steady_clock::time_point started_;
  std::chrono::steady_clock::time_point next_hint_check_;
  std::int64_t promised_ns_ = -1;
  bool exited_ = false;
  std::uint64_t quiescences_ = 0;
};

}  // namespace ubersim::ssl
