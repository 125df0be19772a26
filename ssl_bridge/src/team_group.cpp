#include "ubersim/ssl_bridge/team_group.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <csignal>

namespace ubersim::ssl {
namespace {

// How long one wait for quiescence lasts before the bridge looks at its stop
// flag and at what holds the group back.
constexpr std::chrono::milliseconds kLook{200};

}  // namespace

TeamGroup::TeamGroup(TeamGroupOptions options)
    : options_(std::move(options)), controller_(options_.controller) {}

TeamGroup::~TeamGroup() = default;

void TeamGroup::start() {
  for (const TeamCommand& command : options_.commands) {
    const std::string output = options_.output_dir.empty() ? std::string()
                                                           : options_.output_dir + "/team_" +
                                                                 team_name(command.team) + ".log";
    const pid_t pid = controller_.spawn({"/bin/sh", "-c", command.command}, output);
    pids_.push_back(pid);
    spdlog::info("team {}: started under the time shim (pid {}): {}{}", team_name(command.team),
                 pid, command.command, output.empty() ? "" : ", output in " + output);
  }
}

bool TeamGroup::run_to(std::int64_t until_ns, const AtQuiescence& at_quiescence,
                       const Promise& promise, const ShouldStop& should_stop) {
  for (;;) {
    if (exited_ || should_stop()) return false;
    const timeshim::Quiescence q = controller_.wait_quiescent(kLook);
    report_problems();
    if (q.state == timeshim::GroupState::Exited) {
      exited_ = true;
      spdlog::warn("timeshim: every process of the team group has ended");
      return false;
    }
    if (q.state == timeshim::GroupState::Busy) continue;
    ++quiescences_;
    const std::int64_t now = controller_.now_ns();
    if (at_quiescence(now)) continue;  // it answered the group: let it read that first
    const std::int64_t next = std::max(now, q.next_deadline_ns == timeshim::kNoDeadline
                                                ? until_ns
                                                : std::min(q.next_deadline_ns, until_ns));
    if (next > promised_ns_) {
      promised_ns_ = next;
      promise(next);
    }
    if (next <= now) return true;
    controller_.advance_to(next);
  }
}

void TeamGroup::report_problems() {
  for (const timeshim::Problem& problem : controller_.take_problems()) {
    spdlog::warn("timeshim: {}", problem.text);
  }
}

void TeamGroup::stop() {
  for (pid_t pid : pids_) {
    if (!controller_.exit_status(pid)) ::kill(pid, SIGTERM);
  }
}

}  // namespace ubersim::ssl
