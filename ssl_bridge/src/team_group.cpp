#include "ubersim/ssl_bridge/team_group.hpp"

#include <dirent.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <fstream>
#include <future>
#include <map>
#include <optional>
#include <sstream>

#include "ubersim/spdlog.hpp"
#include "ubersim/ssl_bridge/socket_owner.hpp"

namespace ubersim::ssl {
namespace {

// How long one wait for quiescence lasts before the bridge looks at its stop
// flag and at what holds the group back.
constexpr std::chrono::milliseconds kLook{200};
// Wall time the team programs get to end on SIGTERM (in sim time, run freely).
constexpr std::chrono::milliseconds kEndGrace{500};
// Wall time the group gets, before that, to finish what it does at its sim time.
constexpr std::chrono::milliseconds kSettle{200};
// hint_at_polling judges the speed from this much wall time on (the teams'
// start is slow), and looks again this often.
constexpr std::chrono::seconds kHintAfter{1};
constexpr std::chrono::seconds kHintEvery{1};

// The fields of /proc/<pid>/stat after the comm (which may hold spaces and
// parentheses), from the state (field 3) on; nullopt when the process is gone.
std::optional<std::istringstream> stat_after_comm(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  std::getline(stat, line);
  const auto close = line.rfind(')');
  if (close == std::string::npos) return std::nullopt;
  return std::istringstream(line.substr(close + 1));
}

// The CPU time (s) a process used, with its threads and the children it
// reaped (utime, stime, cutime, cstime: fields 14 to 17); 0 when it is gone.
double cpu_seconds_of(pid_t pid) {
  auto rest = stat_after_comm(pid);
  if (!rest) return 0;
  std::string skipped;
  for (int field = 3; field < 14; ++field) *rest >> skipped;
  unsigned long long ticks[4] = {};
  for (auto& value : ticks) *rest >> value;
  return static_cast<double>(ticks[0] + ticks[1] + ticks[2] + ticks[3]) /
         static_cast<double>(::sysconf(_SC_CLK_TCK));
}

// The parent of every process of this host (of this pid namespace).
std::map<pid_t, pid_t> parents_of_all() {
  std::map<pid_t, pid_t> parent;
  DIR* proc = ::opendir("/proc");
  if (proc == nullptr) return parent;
  while (const dirent* entry = ::readdir(proc)) {
    const pid_t pid = static_cast<pid_t>(std::atoi(entry->d_name));
    if (pid <= 0) continue;
    auto rest = stat_after_comm(pid);
    if (!rest) continue;
    char state = 0;
    pid_t ppid = 0;
    *rest >> state >> ppid;
    parent[pid] = ppid;
  }
  ::closedir(proc);
  return parent;
}

// The index in `ancestors` of the first that pid is or descends from, else
// ancestors.size().
std::size_t ancestor_index(pid_t pid, const std::map<pid_t, pid_t>& parent,
                           const std::vector<pid_t>& ancestors) {
  for (pid_t up = pid; up > 1;) {
    const auto at = std::find(ancestors.begin(), ancestors.end(), up);
    if (at != ancestors.end()) return static_cast<std::size_t>(at - ancestors.begin());
    const auto found = parent.find(up);
    up = found == parent.end() ? 0 : found->second;
  }
  return ancestors.size();
}

// Every process below this one (the bridge is their subreaper, so a team's
// orphaned child is among them too).
std::vector<pid_t> descendants() {
  const std::map<pid_t, pid_t> parent = parents_of_all();
  const std::vector<pid_t> self{::getpid()};
  std::vector<pid_t> below;
  for (const auto& [pid, ppid] : parent) {
    if (pid != self[0] && ancestor_index(pid, parent, self) == 0) below.push_back(pid);
  }
  return below;
}

}  // namespace

TeamGroup::TeamGroup(TeamGroupOptions options) : options_(std::move(options)) {
  // A team's process whose parent ends stays ours, so that stop() finds it.
  ::prctl(PR_SET_CHILD_SUBREAPER, 1);
  for (std::size_t i = 0; i < std::max<std::size_t>(options_.commands.size(), 1); ++i) {
    controllers_.push_back(std::make_unique<timeshim::Controller>(options_.controller));
  }
  group_ended_.assign(controllers_.size(), false);
}

TeamGroup::~TeamGroup() {
  for (pid_t pid : descendants()) ::kill(pid, SIGKILL);
  while (::waitpid(-1, nullptr, WNOHANG) > 0) {
  }
}

void TeamGroup::start() {
  started_ = std::chrono::steady_clock::now();
  next_hint_check_ = started_ + kHintAfter;
  for (std::size_t i = 0; i < options_.commands.size(); ++i) {
    const TeamCommand& command = options_.commands[i];
    const std::string output = options_.output_dir.empty()
                                   ? std::string()
                                   : options_.output_dir + "/team_" + command.colour() + ".log";
    const pid_t pid = controllers_[i]->spawn({"/bin/sh", "-c", command.command}, output);
    pids_.push_back(pid);
    exit_reported_.push_back(false);
    polling_hinted_.push_back(false);
    spdlog::info("team {}: started under the time shim (pid {}): {}{}", command.colour(), pid,
                 command.command, output.empty() ? "" : ", output in " + output);
  }
}

std::int64_t TeamGroup::now_ns() const {
  return controllers_.front()->now_ns();  // advanced together: all alike
}

std::uint64_t TeamGroup::advances() const {
  return controllers_.front()->advances();
}

std::uint64_t TeamGroup::sum_over_groups(std::uint64_t (timeshim::Controller::*count)()
                                             const) const {
  std::uint64_t sum = 0;
  for (const auto& controller : controllers_) sum += ((*controller).*count)();
  return sum;
}

std::uint64_t TeamGroup::turns() const {
  return sum_over_groups(&timeshim::Controller::turns);
}

std::uint64_t TeamGroup::handoffs() const {
  return sum_over_groups(&timeshim::Controller::handoffs);
}

std::uint64_t TeamGroup::charged_pauses() const {
  return sum_over_groups(&timeshim::Controller::charged_pauses);
}

std::uint64_t TeamGroup::full_looks() const {
  return sum_over_groups(&timeshim::Controller::full_looks);
}

std::uint64_t TeamGroup::light_looks() const {
  return sum_over_groups(&timeshim::Controller::light_looks);
}

// Side by side: each group's controller looks at its group (and in
// deterministic mode gives its turns) in a thread of its own, so that one
// team's program runs while the other one's is looked at.
timeshim::Quiescence TeamGroup::wait_quiescent(std::chrono::milliseconds wall_limit) {
  std::vector<std::future<timeshim::Quiescence>> others;
  for (std::size_t i = 1; i < controllers_.size(); ++i) {
    if (group_ended_[i]) continue;
    others.push_back(std::async(std::launch::async, [this, i, wall_limit] {
      return controllers_[i]->wait_quiescent(wall_limit);
    }));
  }
  std::vector<std::pair<std::size_t, timeshim::Quiescence>> answers;
  if (!group_ended_[0]) answers.emplace_back(0, controllers_[0]->wait_quiescent(wall_limit));
  std::size_t next_other = 0;
  for (std::size_t i = 1; i < controllers_.size(); ++i) {
    if (!group_ended_[i]) answers.emplace_back(i, others[next_other++].get());
  }
  timeshim::Quiescence all{timeshim::GroupState::Exited, timeshim::kNoDeadline};
  for (const auto& [i, q] : answers) {
    if (q.state == timeshim::GroupState::Exited) {
      group_ended_[i] = true;
      continue;
    }
    if (all.state != timeshim::GroupState::Busy) all.state = q.state;
    all.next_deadline_ns = std::min(all.next_deadline_ns, q.next_deadline_ns);
  }
  return all;
}

void TeamGroup::advance_to(std::int64_t sim_ns) {
  for (const auto& controller : controllers_) controller->advance_to(sim_ns);
}

bool TeamGroup::run_to(std::int64_t until_ns, const AtQuiescence& at_quiescence,
                       const Promise& promise, const ShouldStop& should_stop) {
  for (;;) {
    if (exited_ || should_stop()) return false;
    const timeshim::Quiescence q = wait_quiescent(kLook);
    report_problems();
    report_exits("");
    hint_at_polling();
    if (q.state == timeshim::GroupState::Exited) {
      exited_ = true;
      spdlog::warn("timeshim: every process of the team group has ended");
      return false;
    }
    if (q.state == timeshim::GroupState::Busy) continue;
    ++quiescences_;
    const std::int64_t now = now_ns();
    if (at_quiescence(now)) continue;  // it answered the group: let it read that first
    const std::int64_t next = std::max(now, q.next_deadline_ns == timeshim::kNoDeadline
                                                ? until_ns
                                                : std::min(q.next_deadline_ns, until_ns));
    if (next > promised_ns_) {
      promised_ns_ = next;
      promise(next);
    }
    if (next <= now) return true;
    advance_to(next);
  }
}

std::size_t TeamGroup::program_of_port(std::uint16_t port) {
  if (const auto known = programs_by_port_.find(port); known != programs_by_port_.end()) {
    return known->second;
  }
  std::size_t program = pids_.size();  // not a team program's: after theirs
  const std::vector<unsigned long> inodes = udp_socket_inodes(port);
  if (!inodes.empty()) {
    const std::map<pid_t, pid_t> parent = parents_of_all();
    for (const auto& [pid, ppid] : parent) {
      const std::size_t owner = ancestor_index(pid, parent, pids_);
      if (owner == pids_.size() || !holds_socket(pid, inodes)) continue;
      program = owner;
      break;
    }
  }
  programs_by_port_[port] = program;
  return program;
}

void TeamGroup::report_problems() {
  for (const auto& controller : controllers_) {
    for (const timeshim::Problem& problem : controller->take_problems()) {
      spdlog::warn("timeshim: {}", problem.text);
    }
  }
}

// Each command's end, once, with its status and the group's sim time: what
// the batch runner reads (docs/batch.md). `when` says why it ended, if known;
// an end of its own during the run is a warning (its team has no control now).
void TeamGroup::report_exits(const char* when) {
  for (std::size_t i = 0; i < pids_.size(); ++i) {
    if (exit_reported_[i]) continue;
    const std::optional<int> status = controllers_[i]->exit_status(pids_[i]);
    if (!status) continue;
    exit_reported_[i] = true;
    spdlog::log(*when == '\0' ? spdlog::level::warn : spdlog::level::info,
                "team {}: the program exited with status {} at sim time {:.3f} s{}",
                options_.commands[i].colour(), *status, static_cast<double>(now_ns()) / 1e9, when);
  }
}

// A thread that polls pauses once per yield_after of charge: a group that
// paused at least that often per game second had a thread polling the whole
// time. When the game then also runs slower than real time, the polling is
// what the wall time goes to (the default charge of 1 us lets a loop spin a
// million times per game second), and the user is told which options trade it.
void TeamGroup::hint_at_polling() {
  const auto wall_now = std::chrono::steady_clock::now();
  if (wall_now < next_hint_check_) return;
  next_hint_check_ = wall_now + kHintEvery;
  const double game_s = static_cast<double>(now_ns()) / 1e9;
  const double wall_s = std::chrono::duration<double>(wall_now - started_).count();
  if (game_s <= 0 || game_s >= wall_s) return;
  const auto& options = options_.controller;
  // Only at the defaults: other values are the user's choice already.
  const timeshim::ControllerOptions defaults;
  if (options.charge_ns != defaults.charge_ns ||
      options.yield_after_ns != defaults.yield_after_ns) {
    return;
  }
  const double pauses_per_polling_thread = 1e9 / static_cast<double>(options.yield_after_ns);
  // A rate of a few pauses says nothing yet.
  constexpr double kPausesToJudge = 50;
  if (game_s * pauses_per_polling_thread < kPausesToJudge) return;
  for (std::size_t i = 0; i < polling_hinted_.size(); ++i) {
    const double pauses_per_game_s =
        static_cast<double>(controllers_[i]->charged_pauses()) / game_s;
    if (polling_hinted_[i] || pauses_per_game_s < pauses_per_polling_thread) continue;
    polling_hinted_[i] = true;
    spdlog::warn(
        "timeshim hint: team {}: threads that poll without blocking paused {:.0f} times per game "
        "second (about {:.0f} polling the whole time, charged {:g} us a call, pausing every {:g} "
        "ms of charge) while the game runs at {:.2f} game s per wall s: a larger "
        "--team-charge-us and --team-yield-after-ms play faster, and the loops then poll less "
        "often per game second (docs/timeshim.md, \"Team programs that poll\")",
        options_.commands[i].colour(), pauses_per_game_s,
        pauses_per_game_s / pauses_per_polling_thread, static_cast<double>(options.charge_ns) / 1e3,
        static_cast<double>(options.yield_after_ns) / 1e6, game_s / wall_s);
  }
}

// What each program cost, from its processes alive now (each with what it
// reaped): what the game's speed owes to the teams' own computing, beside what
// the bridge (mostly the time shim's controllers) cost.
void TeamGroup::report_cpu() const {
  const double game_s = static_cast<double>(now_ns()) / 1e9;
  if (game_s <= 0) return;
  std::vector<double> cpu_s(pids_.size(), 0.0);
  const std::map<pid_t, pid_t> parent = parents_of_all();
  for (const auto& [pid, ppid] : parent) {
    const std::size_t owner = ancestor_index(pid, parent, pids_);
    if (owner < pids_.size()) cpu_s[owner] += cpu_seconds_of(pid);
  }
  rusage own{};
  ::getrusage(RUSAGE_SELF, &own);
  const double bridge_s = static_cast<double>(own.ru_utime.tv_sec + own.ru_stime.tv_sec) +
                          static_cast<double>(own.ru_utime.tv_usec + own.ru_stime.tv_usec) / 1e6;
  std::string text;
  for (std::size_t i = 0; i < pids_.size(); ++i) {
    text += fmt::format("{} {:.1f} s ({:.2f} per game s), ", options_.commands[i].colour(),
                        cpu_s[i], cpu_s[i] / game_s);
  }
  spdlog::info("team CPU: {}the bridge {:.1f} s ({:.2f} per game s), in {:.2f} s of game", text,
               bridge_s, bridge_s / game_s, game_s);
}

void TeamGroup::stop() {
  if (exited_) return;
  report_exits("");
  // The stop comes in wall time, perhaps while the group runs what its last
  // advance woke: let it become quiescent first, so that it ends having done
  // everything up to its sim time (the same output on every run).
  wait_quiescent(kSettle);
  report_cpu();
  for (pid_t pid : descendants()) ::kill(pid, SIGTERM);
  // Their handlers run in sim time: let it run freely for a moment.
  const auto give_up = std::chrono::steady_clock::now() + kEndGrace;
  for (auto now = std::chrono::steady_clock::now(); now < give_up;
       now = std::chrono::steady_clock::now()) {
    const auto q =
        wait_quiescent(std::chrono::duration_cast<std::chrono::milliseconds>(give_up - now));
    if (q.state == timeshim::GroupState::Exited) break;
    if (q.state == timeshim::GroupState::Busy) continue;
    if (q.next_deadline_ns == timeshim::kNoDeadline) break;
    advance_to(q.next_deadline_ns);
  }
  report_problems();
  report_exits(", when the bridge stopped it");
}

}  // namespace ubersim::ssl
