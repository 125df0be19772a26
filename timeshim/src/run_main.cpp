// ubersim_timeshim_run: runs a command under the time shim, on its own sim
// time, as fast as it allows (docs/timeshim.md, "Running a program").
//
//   ubersim_timeshim_run [options] -- COMMAND [ARGS...]
#include <signal.h>
#include <sys/prctl.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "ubersim/cli.hpp"
#include "ubersim/timeshim/controller.hpp"

namespace {

using ubersim::timeshim::Controller;
using ubersim::timeshim::ControllerOptions;
using ubersim::timeshim::GroupState;
using ubersim::timeshim::kNoDeadline;
using ubersim::timeshim::Quiescence;

std::atomic<int> stop_signal{0};
std::atomic<int> stop_requests{0};

void on_stop(int signal_number) {
  stop_signal.store(signal_number);
  stop_requests.fetch_add(1);
}

struct RunOptions {
  ControllerOptions controller;
  double charge_us = 1.0;
  double yield_after_ms = 1.0;
  double epoch_s = 1767225600.0;
  double grace_s = 2.0;
  double duration_s = 0;  // 0: until the command ends
  bool verbose = false;
  std::vector<std::string> command;
};

void print_problems(Controller& group) {
  for (const auto& problem : group.take_problems()) {
    std::fprintf(stderr, "timeshim: %s\n", problem.text.c_str());
  }
}

// Runs the group until it exits; returns the command's exit status.
int run(Controller& group, pid_t command, const RunOptions& options) {
  const std::int64_t until =
      options.duration_s > 0 ? static_cast<std::int64_t>(options.duration_s * 1e9) : kNoDeadline;
  int forwarded = 0;  // stop requests passed on (the first as it came, then SIGKILL)
  auto idle_since = std::chrono::steady_clock::now();
  bool idle_reported = false;
  for (;;) {
    const Quiescence q = group.run_until(until, std::chrono::milliseconds(100));
    print_problems(group);
    const bool reached_end =
        until != kNoDeadline && group.now_ns() >= until && q.state == GroupState::Quiescent;
    const int requests = std::max(stop_requests.load(), reached_end ? 1 : 0);
    if (requests > forwarded) {
      const int first = stop_signal.load() != 0 ? stop_signal.load() : SIGTERM;
      ::kill(command, forwarded > 0 ? SIGKILL : first);
      forwarded = requests;
    }
    if (q.state == GroupState::Exited) break;
    if (q.state != GroupState::Quiescent) {
      idle_since = std::chrono::steady_clock::now();
      continue;
    }
    // Quiescent with nothing due: only input from outside the group can wake it.
    if (!idle_reported && !reached_end &&
        std::chrono::steady_clock::now() - idle_since > options.controller.grace) {
      idle_reported = true;
      std::fprintf(stderr,
                   "timeshim: at sim time %.6f s every thread waits for input with no deadline; "
                   "waiting for input from outside the group\n",
                   static_cast<double>(group.now_ns()) * 1e-9);
    }
    ::usleep(5000);
  }
  if (options.verbose) {
    std::fprintf(stderr,
                 "timeshim: sim time %.6f s, %llu advances, %llu intercepted calls, %llu turns "
                 "(%llu handed over by the shim)\n",
                 static_cast<double>(group.now_ns()) * 1e-9,
                 static_cast<unsigned long long>(group.advances()),
                 static_cast<unsigned long long>(group.intercepted_calls()),
                 static_cast<unsigned long long>(group.turns()),
                 static_cast<unsigned long long>(group.handoffs()));
  }
  return group.exit_status(command).value_or(1);
}

}  // namespace

int main(int argc, char** argv) {
  RunOptions options;
  CLI::App app{
      "Runs COMMAND under the time shim: it and every process it starts read and wait in "
      "simulation time, which advances whenever all of them wait (docs/timeshim.md)."};
  app.add_option("--charge-us", options.charge_us,
                 "sim time (us) charged per intercepted call that does not block")
      ->check(ubersim::at_least(0));
  app.add_option("--yield-after-ms", options.yield_after_ms,
                 "charge (ms) after which a thread that does not block pauses (0: never)")
      ->check(ubersim::at_least(0));
  app.add_option("--epoch", options.epoch_s, "CLOCK_REALTIME at sim time 0 (s since 1970)")
      ->check(ubersim::at_least(0));
  app.add_option("--grace", options.grace_s,
                 "wall seconds before a thread that holds time back is reported")
      ->check(ubersim::at_least(0));
  app.add_option("--duration", options.duration_s,
                 "stop the command with SIGTERM at this sim time (s); 0: run until it ends")
      ->check(ubersim::at_least(0));
  app.add_option("--shim", options.controller.shim_library, "the shim library (default: ../lib)");
  app.add_flag("--deterministic", options.controller.deterministic,
               "run the group's threads one at a time in a fixed order (reproducible "
               "interleaving; slower)");
  app.add_flag("!--look-every-turn", options.controller.shim_handoffs,
               "deterministic mode: a look after every turn, none handed over by the shim (the "
               "same interleaving, slower; for comparison)");
  app.add_flag("-v,--verbose", options.verbose, "print sim time and counts at the end");
  app.add_option("command", options.command, "the command and its arguments (after --)")
      ->required();
  if (const auto stop = ubersim::parse_command_line(app, argc, argv)) return *stop;
  options.controller.charge_ns = static_cast<std::int64_t>(options.charge_us * 1e3);
  options.controller.yield_after_ns = static_cast<std::int64_t>(options.yield_after_ms * 1e6);
  options.controller.realtime_epoch_ns = static_cast<std::int64_t>(options.epoch_s * 1e9);
  options.controller.grace = std::chrono::milliseconds(static_cast<long>(options.grace_s * 1e3));
  ::signal(SIGINT, on_stop);
  ::signal(SIGTERM, on_stop);
  // Orphans of the group come to us, so they stay in the group.
  ::prctl(PR_SET_CHILD_SUBREAPER, 1);
  try {
    Controller group(options.controller);
    const pid_t command = group.spawn(options.command);
    return run(group, command, options);
  } catch (const ubersim::timeshim::UnsupportedProgram& error) {
    std::fprintf(stderr, "ubersim_timeshim_run: %s\n", error.what());
    return 2;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "ubersim_timeshim_run: %s\n", error.what());
    return 1;
  }
}
