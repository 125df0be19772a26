// ubersim_timeshim_bench: what the time shim costs, as ratios against a
// baseline from the same run (docs/timeshim.md, "Cost"):
//  * a clock read under the shim against the same read without it (CPU time
//    per call, measured by the program itself), and likewise an uncontended
//    mutex lock and unlock, without and with the deterministic mode;
//  * sleeps through the controller: sim seconds per wall second of a program
//    that does nothing but sleep 1 ms a thousand times, against the 1x of
//    real time;
//  * the deterministic mode: the wall time of the same sleeps, and of five
//    threads of two processes that compute and sleep (timeshim_probe
//    interleave), in turns against the same under the shim without turns;
//    and four threads passing a baton through a condition variable (probe
//    baton), with the shim handing quiet turns over against a look after
//    every turn.
// Usage: ubersim_timeshim_bench (run from the build tree).
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "temp_folder.hpp"
#include "ubersim/timeshim/controller.hpp"

namespace {

using ubersim::timeshim::Controller;
using ubersim::timeshim::ControllerOptions;
using ubersim::timeshim::GroupState;
using ubersim::timeshim::kNoDeadline;

double value_in(const std::string& path, const std::string& label) {
  std::ifstream in(path);
  std::string name;
  double value = 0;
  while (in >> name >> value) {
    if (name == label) return value;
  }
  return -1;
}

// Runs the probe mode without the shim; returns its output file.
std::string run_plain(const ubersim::test::TempFolder& dir, const char* mode) {
  const std::string output = dir.path(std::string(mode) + ".plain");
  std::fflush(stdout);  // the child's freopen would print what is buffered again
  const pid_t pid = ::fork();
  if (pid == 0) {
    std::freopen(output.c_str(), "w", stdout);
    ::execl(TIMESHIM_PROBE, TIMESHIM_PROBE, mode, static_cast<char*>(nullptr));
    ::_exit(127);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return output;
}

// Runs the probe mode under the shim; returns its output file and the wall seconds.
std::string run_shimmed(const ubersim::test::TempFolder& dir, const char* mode, double* wall_s,
                        bool deterministic = false, bool handoffs = true) {
  ControllerOptions options;
  options.segment_dir = dir.root().string();
  options.yield_after_ns = 0;  // the cost of the call itself, no pauses
  options.deterministic = deterministic;
  options.shim_handoffs = handoffs;
  Controller group(options);
  const std::string output = dir.path(std::string(mode) + (deterministic ? ".turns" : ".shim") +
                                      (handoffs ? "" : ".looks"));
  const auto start = std::chrono::steady_clock::now();
  group.spawn({TIMESHIM_PROBE, mode}, output);
  while (group.run_until(kNoDeadline, std::chrono::seconds(5)).state != GroupState::Exited) {
  }
  *wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return output;
}

}  // namespace

int main() {
  ubersim::test::TempFolder dir("timeshim_bench");
  double wall_s = 0;
  const double plain = value_in(run_plain(dir, "clock_cost"), "ns_per_clock_read");
  const double shimmed = value_in(run_shimmed(dir, "clock_cost", &wall_s), "ns_per_clock_read");
  std::printf("clock read under the shim: %.2fx the CPU time of a plain one\n", shimmed / plain);
  const double plain_lock = value_in(run_plain(dir, "mutex_cost"), "ns_per_lock_unlock");
  const double shimmed_lock =
      value_in(run_shimmed(dir, "mutex_cost", &wall_s), "ns_per_lock_unlock");
  const double turns_lock =
      value_in(run_shimmed(dir, "mutex_cost", &wall_s, true), "ns_per_lock_unlock");
  std::printf(
      "uncontended mutex lock and unlock under the shim: %.2fx the CPU time of a plain one, "
      "%.2fx in deterministic mode\n",
      shimmed_lock / plain_lock, turns_lock / plain_lock);
  const double sim_s = value_in(run_shimmed(dir, "sleep_cost", &wall_s), "end");
  std::printf("1000 sleeps of 1 ms through the controller: %.1fx real time (sim s per wall s)\n",
              sim_s / wall_s);
  double turns_wall_s = 0;
  run_shimmed(dir, "sleep_cost", &turns_wall_s, true);
  std::printf("the same sleeps in deterministic mode: %.2fx the wall time\n",
              turns_wall_s / wall_s);
  run_shimmed(dir, "interleave", &wall_s);
  run_shimmed(dir, "interleave", &turns_wall_s, true);
  std::printf(
      "5 threads of 2 processes computing and sleeping (probe interleave) in deterministic mode: "
      "%.2fx the wall time\n",
      turns_wall_s / wall_s);
  double looks_wall_s = 0;
  run_shimmed(dir, "baton", &looks_wall_s, true, false);
  run_shimmed(dir, "baton", &turns_wall_s, true);
  std::printf(
      "4 threads passing a baton through a condition variable (probe baton) in deterministic "
      "mode, quiet turns handed over by the shim: %.2fx the wall time of a look after every turn\n",
      turns_wall_s / looks_wall_s);
  dir.succeeded();
  return 0;
}
