// The time shim with real programs (docs/timeshim.md, "Tests"): C++ and
// Python programs run under libubersim_timeshim.so while a Controller in this
// process drives their sim time; each prints "label seconds" for what it saw.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "child_process.hpp"
#include "read_file.hpp"
#include "temp_dir.hpp"
#include "ubersim/timeshim/controller.hpp"

namespace ubersim::timeshim {
namespace {

using ubersim::test::TempDir;

constexpr double kEpoch = 1767225600.0;  // ControllerOptions' default, in s

using ubersim::test::read_file;

// The "label value" lines a probe printed, in order.
using Seen = std::vector<std::pair<std::string, double>>;

Seen parse(const std::string& output) {
  Seen seen;
  std::istringstream in(output);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string label;
    double value = 0;
    if (fields >> label >> value) seen.emplace_back(label, value);
  }
  return seen;
}

double value_of(const Seen& seen, const std::string& label) {
  for (const auto& [name, value] : seen) {
    if (name == label) return value;
  }
  ADD_FAILURE() << "no line '" << label << "'";
  return -1;
}

struct GroupRun {
  std::string output;
  Seen seen;
  int exit_status = -1;
  double wall_s = 0;
  std::int64_t sim_ns = 0;
  std::uint64_t advances = 0;
  std::uint64_t turns = 0;     // deterministic mode
  std::uint64_t handoffs = 0;  // of those, handed over by the shim (shim/handoff.cpp)
  std::uint64_t calls = 0;     // intercepted calls
  std::uint64_t pauses = 0;    // charged pauses
  std::uint64_t full_looks = 0;
  std::uint64_t light_looks = 0;  // deterministic mode, after a turn
  std::vector<Problem> problems;
};

// The problems that name a blocking call (not a thread a loaded machine kept
// running for longer than the grace).
std::vector<Problem> blocking_problems(const GroupRun& run) {
  std::vector<Problem> found;
  for (const auto& problem : run.problems) {
    if (problem.text.find("is blocked in") != std::string::npos) found.push_back(problem);
  }
  return found;
}

std::string all_text(const std::vector<Problem>& problems) {
  std::string text;
  for (const auto& problem : problems) text += problem.text + "\n";
  return text;
}

ControllerOptions options_in(const TempDir& dir) {
  ControllerOptions options;
  options.segment_dir = dir.root().string();
  return options;
}

// Runs the group as fast as it allows until it exits (at most 60 s of wall time).
GroupRun run_to_end(Controller& group, pid_t pid, const std::string& output_path) {
  GroupRun run;
  const auto start = std::chrono::steady_clock::now();
  for (;;) {
    const Quiescence q = group.run_until(kNoDeadline, std::chrono::milliseconds(200));
    for (auto& problem : group.take_problems()) run.problems.push_back(std::move(problem));
    if (q.state == GroupState::Exited) break;
    if (std::chrono::steady_clock::now() - start > std::chrono::seconds(60)) {
      ADD_FAILURE() << "the group did not end within 60 s of wall time; problems found:\n"
                    << all_text(run.problems);
      break;
    }
    if (q.state == GroupState::Quiescent) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  run.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.exit_status = group.exit_status(pid).value_or(-1);
  run.sim_ns = group.now_ns();
  run.advances = group.advances();
  run.turns = group.turns();
  run.handoffs = group.handoffs();
  run.calls = group.intercepted_calls();
  run.pauses = group.charged_pauses();
  run.full_looks = group.full_looks();
  run.light_looks = group.light_looks();
  run.output = read_file(output_path);
  run.seen = parse(run.output);
  return run;
}

GroupRun run_program(const TempDir& dir, const std::vector<std::string>& argv,
                     ControllerOptions options) {
  Controller group(std::move(options));
  const std::string output = dir.path("output.txt");
  const pid_t pid = group.spawn(argv, output);
  return run_to_end(group, pid, output);
}

GroupRun run_probe(const TempDir& dir, const std::string& mode) {
  return run_program(dir, {TIMESHIM_PROBE, mode}, options_in(dir));
}

bool have_python() {
  return ::access("/usr/bin/python3", X_OK) == 0;
}

TEST(Timeshim, SleepsTakeSimTimeNotWallTime) {
  TempDir dir;
  const GroupRun run = run_probe(dir, "sleeps");
  ASSERT_EQ(run.exit_status, 0) << run.output;
  EXPECT_DOUBLE_EQ(value_of(run.seen, "start"), 0.0);
  EXPECT_DOUBLE_EQ(value_of(run.seen, "nanosleep"), 1.0);
  EXPECT_DOUBLE_EQ(value_of(run.seen, "usleep"), 1.5);
  EXPECT_DOUBLE_EQ(value_of(run.seen, "sleep"), 3.5);
  EXPECT_DOUBLE_EQ(value_of(run.seen, "clock_nanosleep_abs"), 6.5);
  EXPECT_DOUBLE_EQ(value_of(run.seen, "sleep_for"), 8.0);
  EXPECT_DOUBLE_EQ(value_of(run.seen, "steady_clock"), 8.0);
  EXPECT_DOUBLE_EQ(value_of(run.seen, "gettimeofday"), kEpoch + 8.0);
  EXPECT_DOUBLE_EQ(value_of(run.seen, "time"), kEpoch + 8.0);
  EXPECT_DOUBLE_EQ(value_of(run.seen, "system_clock"), kEpoch + 8.0);
  EXPECT_EQ(run.sim_ns, 8000000000);
  // 8 s of sleeps in far less wall time: nothing waited for the wall clock.
  EXPECT_LT(run.wall_s, 4.0);
  EXPECT_TRUE(blocking_problems(run).empty()) << all_text(run.problems);
}

TEST(Timeshim, FdWaitTimeoutsEndAtTheirSimDeadline) {
  TempDir dir;
  const GroupRun run = run_probe(dir, "fd_timeouts");
  ASSERT_EQ(run.exit_status, 0) << run.output;
  EXPECT_DOUBLE_EQ(value_of(run.seen, "select"), 0.25);
  EXPECT_DOUBLE_EQ(value_of(run.seen, "poll"), 1.0);
  EXPECT_DOUBLE_EQ(value_of(run.seen, "epoll_wait"), 3.0);
  // Readiness before the deadline ends the wait then (a writer at +100 ms).
  EXPECT_DOUBLE_EQ(value_of(run.seen, "poll_ready"), 3.1);
  // select, poll and epoll_wait timed out (0), the last poll saw 1 fd ready.
  EXPECT_DOUBLE_EQ(value_of(run.seen, "results"), 1.0);
}

TEST(Timeshim, SocketReceiveTimeoutEndsInSimTime) {
  TempDir dir;
  const GroupRun run = run_probe(dir, "receive_timeout");
  ASSERT_EQ(run.exit_status, 0) << run.output;
  EXPECT_DOUBLE_EQ(value_of(run.seen, "recv_timed_out"), 1.5);
  EXPECT_DOUBLE_EQ(value_of(run.seen, "read_timed_out"), 3.0);
  EXPECT_DOUBLE_EQ(value_of(run.seen, "timeout"), 1.5);
  EXPECT_LT(run.wall_s, 2.5);  // 3 s of sim time
}

TEST(Timeshim, TimerfdExpiresInSimTime) {
  TempDir dir;
  const GroupRun run = run_probe(dir, "timer_fd");
  ASSERT_EQ(run.exit_status, 0) << run.output;
  const Seen expected = {{"expired", 0.5}, {"expired", 0.75},       {"expired", 1.0},
                         {"count", 2.0},   {"epoll_expired", 1.75}, {"left", 0.25}};
  ASSERT_EQ(run.seen.size(), expected.size()) << run.output;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(run.seen[i].first, expected[i].first);
    EXPECT_NEAR(run.seen[i].second, expected[i].second, 1e-9) << run.seen[i].first;
  }
}

TEST(Timeshim, TimedConditionAndSemaphoreWaitsEndInSimTime) {
  TempDir dir;
  const GroupRun run = run_probe(dir, "cond_waits");
  ASSERT_EQ(run.exit_status, 0) << run.output;
  EXPECT_NEAR(value_of(run.seen, "wait_for"), 0.3, 1e-9);
  EXPECT_NEAR(value_of(run.seen, "wait_until_system"), 0.5, 1e-9);
  EXPECT_NEAR(value_of(run.seen, "timedwait_monotonic"), 1.5, 1e-9);
  EXPECT_NEAR(value_of(run.seen, "sem_timedwait"), 1.75, 1e-9);
  EXPECT_NEAR(value_of(run.seen, "notified"), 1.85, 1e-9);
}

TEST(Timeshim, TimedMutexLocksEndInSimTime) {
  TempDir dir;
  const GroupRun run = run_probe(dir, "timed_mutex");
  ASSERT_EQ(run.exit_status, 0) << run.output;
  // From the moment the holder has the mutex (until 2 s).
  const double start = value_of(run.seen, "start");
  EXPECT_NEAR(value_of(run.seen, "try_lock_for") - start, 0.3, 1e-9);
  EXPECT_NEAR(value_of(run.seen, "try_lock_until_system") - start, 0.5, 1e-9);
  EXPECT_NEAR(value_of(run.seen, "timedlock") - start, 0.75, 1e-9);
  EXPECT_NEAR(value_of(run.seen, "locked"), 2.0, 1e-9);  // unlocked before its deadline
  EXPECT_LT(run.wall_s, 1.5);
}

TEST(Timeshim, SendAndAcceptTimeoutsEndInSimTime) {
  TempDir dir;
  const GroupRun run = run_probe(dir, "socket_send_accept");
  ASSERT_EQ(run.exit_status, 0) << run.output;
  EXPECT_DOUBLE_EQ(value_of(run.seen, "send_timed_out"), 1.25);
  EXPECT_DOUBLE_EQ(value_of(run.seen, "write_timed_out"), 2.5);
  EXPECT_DOUBLE_EQ(value_of(run.seen, "send_timeout"), 1.25);
  EXPECT_DOUBLE_EQ(value_of(run.seen, "accept_timed_out"), 3.25);
  EXPECT_DOUBLE_EQ(value_of(run.seen, "accepted"), 3.5);  // a connection before the deadline
  EXPECT_LT(run.wall_s, 2.0);
}

TEST(Timeshim, PosixTimersAlarmsAndSignalWaitsRunOnSimTime) {
  TempDir dir;
  const GroupRun run = run_probe(dir, "signal_timers");
  ASSERT_EQ(run.exit_status, 0) << run.output;
  const Seen expected = {{"timer_signal", 0.5}, {"timer_signal", 0.75}, {"timer_signal", 1.0},
                         {"timer_left", 0.25},  {"timer_thread", 1.5},  {"sigtimedwait", 1.9},
                         {"epoll_pwait2", 2.0}, {"alarm_left", 2.0},    {"alarm", 4.0},
                         {"setitimer", 4.5},    {"itimer_left", 0.25}};
  ASSERT_EQ(run.seen.size(), expected.size()) << run.output;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(run.seen[i].first, expected[i].first);
    EXPECT_NEAR(run.seen[i].second, expected[i].second, 1e-9) << run.seen[i].first;
  }
  EXPECT_LT(run.wall_s, 2.5);  // 4.5 s of sim time
}

TEST(Timeshim, SignalsBetweenProcessesEndSleepsAtTheSimTimeTheyAreSent) {
  TempDir dir;
  const GroupRun run = run_probe(dir, "signal_wake");
  ASSERT_EQ(run.exit_status, 0) << run.output;
  ASSERT_EQ(run.seen.size(), 4U) << run.output;
  EXPECT_EQ(run.seen[0].first, "parent_woken");
  EXPECT_NEAR(run.seen[0].second, 1.0, 1e-3) << run.output;  // not at its 10 s
  EXPECT_EQ(run.seen[1], (std::pair<std::string, double>{"value", 7.0}));
  EXPECT_EQ(run.seen[2].first, "child_woken");
  EXPECT_NEAR(run.seen[2].second, 1.5, 1e-3) << run.output;  // not at its 21 s
  EXPECT_EQ(run.seen[3].first, "end");
  EXPECT_NEAR(run.seen[3].second, 1.5, 1e-3) << run.output;
}

TEST(Timeshim, ThreadsEachWaitTheirOwnSimTime) {
  TempDir dir;
  const GroupRun run = run_probe(dir, "threads");
  ASSERT_EQ(run.exit_status, 0) << run.output;
  Seen expected;
  for (int worker = 1; worker <= 3; ++worker) {
    for (int i = 1; i <= 4; ++i)
      expected.emplace_back("thread" + std::to_string(worker), 0.1 * worker * i);
  }
  expected.emplace_back("end", 1.2);
  ASSERT_EQ(run.seen.size(), expected.size()) << run.output;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(run.seen[i].first, expected[i].first);
    EXPECT_NEAR(run.seen[i].second, expected[i].second, 1e-9) << run.seen[i].first;
  }
}

TEST(Timeshim, ForkedChildIsInTheGroup) {
  TempDir dir;
  const GroupRun run = run_probe(dir, "forks");
  ASSERT_EQ(run.exit_status, 0) << run.output;
  EXPECT_DOUBLE_EQ(value_of(run.seen, "parent"), 0.5);
  EXPECT_DOUBLE_EQ(value_of(run.seen, "child"), 2.0);
  EXPECT_DOUBLE_EQ(value_of(run.seen, "reaped"), 2.0);
}

// One thread in poll() with no timeout, one in a plain blocking recv(): both
// wait for input, none for time; datagrams from outside wake them.
void check_quiescent_on_sockets(bool deterministic) {
  TempDir dir;
  ControllerOptions options = options_in(dir);
  options.deterministic = deterministic;
  Controller group(options);
  const std::string output = dir.path("output.txt");
  const pid_t pid = group.spawn({TIMESHIM_PROBE, "socket_wait"}, output);
  // One thread in poll() with no timeout, one in a plain blocking recv():
  // both wait for input, none for time.
  const Quiescence q = group.run_until(kNoDeadline, std::chrono::seconds(20));
  ASSERT_EQ(q.state, GroupState::Quiescent);
  EXPECT_EQ(q.next_deadline_ns, kNoDeadline);
  EXPECT_EQ(group.now_ns(), 0);
  // Quiescent means both threads sleep in their waits now.
  const std::string tasks = "/proc/" + std::to_string(pid) + "/task";
  int sleeping = 0;
  for (const auto& task : std::filesystem::directory_iterator(tasks)) {
    const std::string stat = read_file(task.path().string() + "/stat");
    sleeping += stat.substr(stat.rfind(')') + 2, 1) == "S" ? 1 : 0;
  }
  EXPECT_EQ(sleeping, 2);
  int poll_port = 0, recv_port = 0;
  for (int i = 0; i < 200 && recv_port == 0; ++i) {
    std::sscanf(read_file(output).c_str(), "ports %d %d", &poll_port, &recv_port);
    if (recv_port == 0) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_NE(recv_port, 0) << read_file(output);
  // Input from outside the group wakes it.
  const int sender = ::socket(AF_INET, SOCK_DGRAM, 0);
  for (int port : {poll_port, recv_port}) {
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_port = htons(static_cast<std::uint16_t>(port));
    to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ASSERT_EQ(::sendto(sender, "hello", 5, 0, reinterpret_cast<sockaddr*>(&to), sizeof(to)), 5);
  }
  ::close(sender);
  const GroupRun run = run_to_end(group, pid, output);
  EXPECT_EQ(run.exit_status, 0) << run.output;
  EXPECT_DOUBLE_EQ(value_of(run.seen, "poll_woke"), 0.0);
  EXPECT_DOUBLE_EQ(value_of(run.seen, "received"), 5.0);
}

TEST(Timeshim, QuiescentWhileEveryThreadWaitsOnASocket) {
  check_quiescent_on_sockets(false);
}

TEST(Timeshim, QuiescentWhileEveryThreadWaitsOnASocketInDeterministicMode) {
  check_quiescent_on_sockets(true);
}

TEST(Timeshim, RunUntilStopsAtTheGivenSimTime) {
  TempDir dir;
  Controller group(options_in(dir));
  const std::string output = dir.path("output.txt");
  const pid_t pid = group.spawn({TIMESHIM_PROBE, "sleeps"}, output);
  // The simulation says "advance to 2 s": the group has done everything up
  // to 2 s (its sleeps ending at 1 and 1.5 s) and waits for 3.5 s.
  const Quiescence q = group.run_until(2000000000, std::chrono::seconds(20));
  ASSERT_EQ(q.state, GroupState::Quiescent);
  EXPECT_EQ(group.now_ns(), 2000000000);
  EXPECT_EQ(q.next_deadline_ns, 3500000000);
  const Seen so_far = parse(read_file(output));
  ASSERT_EQ(so_far.size(), 3U) << read_file(output);
  EXPECT_EQ(so_far[2].first, "usleep");
  const GroupRun run = run_to_end(group, pid, output);
  EXPECT_EQ(run.exit_status, 0);
  EXPECT_DOUBLE_EQ(value_of(run.seen, "sleep_for"), 8.0);
}

TEST(Timeshim, PollingLoopIsChargedAndEnds) {
  TempDir dir;
  ControllerOptions options = options_in(dir);
  options.charge_ns = 1000;
  options.yield_after_ns = 1000000;
  const GroupRun run = run_program(dir, {TIMESHIM_PROBE, "busy_clock"}, options);
  ASSERT_EQ(run.exit_status, 0) << run.output;
  // 1 s of sim time at 1 us per clock read, after 2000 free reads.
  EXPECT_NEAR(value_of(run.seen, "reads"), 1002000, 10);
  EXPECT_NEAR(value_of(run.seen, "end"), 1.0, 1e-5);
  EXPECT_NEAR(static_cast<double>(run.advances), 1000, 2);  // one pause per 1 ms of charge
  EXPECT_NEAR(static_cast<double>(run.pauses), 1000, 2);    // and the group counted them
}

TEST(Timeshim, PollingThreadsPauseAtTheSameInstants) {
  TempDir dir;
  ControllerOptions options = options_in(dir);
  options.charge_ns = 1000;
  options.yield_after_ns = 1000000;
  const GroupRun run = run_program(dir, {TIMESHIM_PROBE, "busy_clock_two"}, options);
  ASSERT_EQ(run.exit_status, 0) << run.output;
  EXPECT_GE(value_of(run.seen, "end"), 1.0);
  // Paused on one grid of 1 ms: about one advance per ms for both (each
  // pausing at its own charge would take about two).
  EXPECT_LT(static_cast<double>(run.advances), 1100);
  EXPECT_NEAR(static_cast<double>(run.pauses), 2000, 4);  // each thread's own
}

TEST(Timeshim, UnsupportedBlockingCallIsNamedNotHung) {
  TempDir dir;
  ControllerOptions options = options_in(dir);
  options.grace = std::chrono::milliseconds(500);
  const GroupRun run = run_program(dir, {TIMESHIM_PROBE, "raw_sleep"}, options);
  EXPECT_EQ(run.exit_status, 0) << run.output;
  const std::vector<Problem> blocked = blocking_problems(run);
  ASSERT_EQ(blocked.size(), 1U) << all_text(run.problems);
  EXPECT_NE(blocked[0].text.find("blocked in nanosleep"), std::string::npos) << blocked[0].text;
  EXPECT_NE(blocked[0].text.find("timeshim_probe"), std::string::npos) << blocked[0].text;
  EXPECT_NE(blocked[0].tid, 0);
}

TEST(Timeshim, StaticProgramIsRefusedAtStart) {
  TempDir dir;
  Controller group(options_in(dir));
  EXPECT_THROW(group.spawn({TIMESHIM_STATIC_PROBE}), UnsupportedProgram);
}

TEST(Timeshim, StaticProgramStartedByTheGroupIsNamed) {
  TempDir dir;
  const GroupRun run =
      run_program(dir, {TIMESHIM_PROBE, "exec_static", TIMESHIM_STATIC_PROBE}, options_in(dir));
  EXPECT_EQ(run.exit_status, 0) << run.output;
  bool named = false;
  for (const auto& problem : run.problems) {
    named = named || problem.text.find("statically linked") != std::string::npos;
  }
  EXPECT_TRUE(named) << all_text(run.problems);
}

TEST(Timeshim, ProgramThatReadsTheClockWithoutLibcIsRefusedAtStart) {
  TempDir dir;
  Controller group(options_in(dir));
  try {
    group.spawn({TIMESHIM_GO_LIKE_PROBE});
    ADD_FAILURE() << "spawn accepted a Go-like program";
  } catch (const UnsupportedProgram& error) {
    EXPECT_NE(std::string(error.what()).find("Go program"), std::string::npos) << error.what();
  }
}

TEST(Timeshim, ProgramThatReadsTheClockWithoutLibcStartedByTheGroupIsNamed) {
  TempDir dir;
  const GroupRun run =
      run_program(dir, {TIMESHIM_PROBE, "exec_static", TIMESHIM_GO_LIKE_PROBE}, options_in(dir));
  EXPECT_EQ(run.exit_status, 0) << run.output;
  bool named = false;
  for (const auto& problem : run.problems) {
    named =
        named || (problem.text.find("sees wall time: it is a Go program") != std::string::npos &&
                  problem.text.find("timeshim_go_like") != std::string::npos);
  }
  EXPECT_TRUE(named) << all_text(run.problems);
}

TEST(Timeshim, PythonProgramRunsOnSimTime) {
  if (!have_python()) GTEST_SKIP() << "no /usr/bin/python3";
  TempDir dir;
  const GroupRun run = run_program(dir, {"/usr/bin/python3", TIMESHIM_PROBE_PY}, options_in(dir));
  ASSERT_EQ(run.exit_status, 0) << run.output;
  const Seen expected = {{"start", 0.0},
                         {"sleep", 1.0},
                         {"time", kEpoch + 1.0},
                         {"select", 1.5},
                         {"selector", 1.75},
                         {"socket_timeout", 3.75},
                         {"main_while_waiting", 4.25},
                         {"event_wait", 5.25},
                         {"child", 6.0},
                         {"end", 6.0}};
  ASSERT_EQ(run.seen.size(), expected.size()) << run.output;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(run.seen[i].first, expected[i].first);
    EXPECT_NEAR(run.seen[i].second, expected[i].second, 1e-6) << run.seen[i].first;
  }
  EXPECT_TRUE(blocking_problems(run).empty()) << all_text(run.problems);
}

TEST(Timeshim, RerunsSeeTheSameSimTimesAlsoBesideACpuHog) {
  TempDir dir;
  std::vector<std::vector<std::string>> programs = {
      {TIMESHIM_PROBE, "threads"}, {TIMESHIM_PROBE, "fd_timeouts"}, {TIMESHIM_PROBE, "cond_waits"}};
  if (have_python()) programs.push_back({"/usr/bin/python3", TIMESHIM_PROBE_PY});
  for (const auto& argv : programs) {
    const GroupRun first = run_program(dir, argv, options_in(dir));
    // The second beside a CPU hog on every core: the wall clock's pace must
    // not show in what the program sees.
    std::atomic<bool> hogging{true};
    std::vector<std::thread> hogs;
    for (unsigned i = 0; i < std::max(1U, std::thread::hardware_concurrency()); ++i) {
      hogs.emplace_back([&hogging] {
        while (hogging.load(std::memory_order_relaxed)) {
        }
      });
    }
    const GroupRun second = run_program(dir, argv, options_in(dir));
    hogging.store(false);
    for (auto& hog : hogs) hog.join();
    EXPECT_FALSE(first.output.empty());
    EXPECT_EQ(first.output, second.output) << argv.back();
  }
}

// Runs fn (a group run) beside a CPU hog on every core.
template <typename Fn>
GroupRun beside_cpu_hog(Fn&& fn) {
  std::atomic<bool> hogging{true};
  std::vector<std::thread> hogs;
  for (unsigned i = 0; i < std::max(1U, std::thread::hardware_concurrency()); ++i) {
    hogs.emplace_back([&hogging] {
      while (hogging.load(std::memory_order_relaxed)) {
      }
    });
  }
  GroupRun run = fn();
  hogging.store(false);
  for (auto& hog : hogs) hog.join();
  return run;
}

ControllerOptions deterministic_in(const TempDir& dir) {
  ControllerOptions options = options_in(dir);
  options.deterministic = true;
  return options;
}

// The lengths of the runs of equal items in `items`, with the item of each.
template <typename T>
std::vector<std::pair<T, int>> runs_of(const std::vector<T>& items) {
  std::vector<std::pair<T, int>> runs;
  for (const T& item : items) {
    if (runs.empty() || runs.back().first != item) runs.emplace_back(item, 0);
    ++runs.back().second;
  }
  return runs;
}

TEST(Timeshim, DeterministicModeRunsThreadsOfProcessesInAFixedOrder) {
  TempDir dir;
  // Five threads of two processes write 30 letters each to one file, 10
  // between sleeps, with CPU work between letters. In turns, each writes
  // its 10 at once (without the mode the kernel interleaves them).
  const std::vector<std::string> argv = {TIMESHIM_PROBE, "interleave"};
  const GroupRun first = run_program(dir, argv, deterministic_in(dir));
  ASSERT_EQ(first.exit_status, 0) << first.output;
  const std::string letters = first.output.substr(0, first.output.find('\n'));
  ASSERT_EQ(letters.size(), 150U) << first.output;
  const auto runs = runs_of(std::vector<char>(letters.begin(), letters.end()));
  ASSERT_EQ(runs.size(), 15U) << letters;
  std::map<char, int> per_letter;
  for (const auto& [letter, length] : runs) {
    EXPECT_EQ(length, 10) << letters;
    ++per_letter[letter];
  }
  EXPECT_EQ(per_letter, (std::map<char, int>{{'A', 3}, {'B', 3}, {'C', 3}, {'D', 3}, {'E', 3}}));
  const GroupRun second =
      beside_cpu_hog([&] { return run_program(dir, argv, deterministic_in(dir)); });
  EXPECT_EQ(first.output, second.output);
  // Not only what it wrote: the same turns, and the same calls in them.
  EXPECT_EQ(first.turns, second.turns);
  EXPECT_EQ(first.calls, second.calls);
  // Looks after turns were light ones (light_look.cpp), in numbers that
  // depend on the machine (a thread created anywhere makes the next look a
  // full one), and the order stayed the same.
  EXPECT_GT(first.light_looks, 0U);
  EXPECT_GT(second.light_looks, 0U);
  EXPECT_TRUE(blocking_problems(second).empty()) << all_text(second.problems);
}

TEST(Timeshim, DeterministicModeRunsPythonThreadsAndAForkedChildInAFixedOrder) {
  if (!have_python()) GTEST_SKIP() << "no /usr/bin/python3";
  TempDir dir;
  const std::vector<std::string> argv = {"/usr/bin/python3", TIMESHIM_DET_PY};
  const GroupRun first = run_program(dir, argv, deterministic_in(dir));
  ASSERT_EQ(first.exit_status, 0) << first.output;
  // 5 threads (3 here, 2 in the child) print 15 lines each, 5 between sleeps:
  // in turns, the 5 of each come together.
  std::vector<std::string> names;
  for (const auto& [label, value] : first.seen) {
    if (label != "end" && label != "pool") names.push_back(label);
  }
  ASSERT_EQ(names.size(), 75U) << first.output;
  for (const auto& [name, length] : runs_of(names)) EXPECT_EQ(length, 5) << first.output;
  EXPECT_DOUBLE_EQ(value_of(first.seen, "pool"), 55.0);  // 0 + 1 + 4 + 9 + 16 + 25
  const GroupRun second =
      beside_cpu_hog([&] { return run_program(dir, argv, deterministic_in(dir)); });
  EXPECT_EQ(first.output, second.output);
  EXPECT_EQ(first.turns, second.turns);
  EXPECT_EQ(first.calls, second.calls);
  // Looks after turns were light ones (light_look.cpp), in numbers that
  // depend on the machine (a thread created anywhere makes the next look a
  // full one), and the order stayed the same.
  EXPECT_GT(first.light_looks, 0U);
  EXPECT_GT(second.light_looks, 0U);
}

// A turn that changed nothing a look relies on is handed to the next thread
// by the shim (shim/handoff.cpp): the same interleaving as with a look after
// every turn, also beside a CPU hog. Four threads pass a baton through a
// condition variable, each broadcast waking all (who woke in which order is
// hashed), and CPython's threads hand the GIL on.
TEST(Timeshim, DeterministicModeHandsQuietTurnsOverInTheSameOrderAsItsLooks) {
  TempDir dir;
  std::vector<std::vector<std::string>> programs = {{TIMESHIM_PROBE, "baton"}};
  if (have_python()) programs.push_back({"/usr/bin/python3", TIMESHIM_DET_PY});
  for (const auto& argv : programs) {
    ControllerOptions looks = deterministic_in(dir);
    looks.shim_handoffs = false;
    const GroupRun looked = run_program(dir, argv, looks);
    ASSERT_EQ(looked.exit_status, 0) << looked.output;
    EXPECT_EQ(looked.handoffs, 0U);
    const GroupRun handed = run_program(dir, argv, deterministic_in(dir));
    EXPECT_EQ(handed.output, looked.output) << argv.back();
    EXPECT_EQ(handed.turns, looked.turns) << argv.back();
    EXPECT_EQ(handed.calls, looked.calls) << argv.back();
    // How many depends on the machine (a thread created anywhere makes the
    // next look a full one, and a turn after it goes through the controller).
    EXPECT_GT(handed.handoffs, 0U) << argv.back();
    const GroupRun beside_hog =
        beside_cpu_hog([&] { return run_program(dir, argv, deterministic_in(dir)); });
    EXPECT_EQ(beside_hog.output, looked.output) << argv.back();
    EXPECT_EQ(beside_hog.turns, looked.turns) << argv.back();
    EXPECT_TRUE(blocking_problems(beside_hog).empty()) << all_text(beside_hog.problems);
  }
}

TEST(Timeshim, DeterministicModeGivesPythonTheSameHashesAndRandomBytesOnEveryRun) {
  if (!have_python()) GTEST_SKIP() << "no /usr/bin/python3";
  TempDir dir;
  // CPython seeds its str hashes at random per process, and the order of a
  // set of strings follows them: the mode sets PYTHONHASHSEED (to 0). Its
  // random module and uuid4 take their seed and bytes from getrandom, which
  // the mode serves from a stream of the thread's place in the group; a
  // forked child gets a stream of its own.
  const std::vector<std::string> argv = {
      "/usr/bin/python3", "-c",
      "import os, random, uuid\n"
      "print(hash('ubersim'), list({'kick', 'pass', 'dribble', 'chip', 'block', 'mark'}))\n"
      "print(os.urandom(8).hex(), random.random(), uuid.uuid4())\n"
      "r, w = os.pipe()\n"
      "if os.fork() == 0:\n"
      "    os.write(w, os.urandom(8).hex().encode()); os._exit(0)\n"
      "os.wait(); child = os.read(r, 16).decode()\n"
      "print('child', child, child != os.urandom(8).hex())\n"};
  const GroupRun first = run_program(dir, argv, deterministic_in(dir));
  ASSERT_EQ(first.exit_status, 0) << first.output;
  EXPECT_NE(first.output.find(" True\n"), std::string::npos) << first.output;
  const GroupRun second = run_program(dir, argv, deterministic_in(dir));
  EXPECT_EQ(first.output, second.output);
}

TEST(Timeshim, DeterministicModeKeepsTheSimTimesOfEveryWait) {
  TempDir dir;
  std::vector<std::vector<std::string>> programs = {{TIMESHIM_PROBE, "threads"},
                                                    {TIMESHIM_PROBE, "fd_timeouts"},
                                                    {TIMESHIM_PROBE, "cond_waits"},
                                                    {TIMESHIM_PROBE, "forks"},
                                                    {TIMESHIM_PROBE, "socket_send_accept"},
                                                    {TIMESHIM_PROBE, "signal_timers"},
                                                    {TIMESHIM_PROBE, "signal_wake"}};
  if (have_python()) programs.push_back({"/usr/bin/python3", TIMESHIM_PROBE_PY});
  for (const auto& argv : programs) {
    const GroupRun plain = run_program(dir, argv, options_in(dir));
    const GroupRun in_turns = run_program(dir, argv, deterministic_in(dir));
    EXPECT_EQ(in_turns.exit_status, 0) << in_turns.output;
    EXPECT_FALSE(plain.output.empty());
    EXPECT_EQ(plain.output, in_turns.output) << argv.back();
    EXPECT_TRUE(blocking_problems(in_turns).empty()) << all_text(in_turns.problems);
  }
}

// After a turn that output nothing to an fd, a light look does not read the
// threads that wait for input (light_look.cpp). Each kind of output must
// still be seen: its reader, woken by it, runs at the sim time of the
// output, not after the writer's next sleep moved sim time on. Beside a CPU
// hog the woken reader is slow to get a core, so that a look that skipped it
// would call the group quiescent with the reader on its way.
TEST(Timeshim, DeterministicModeSeesEveryOutputThatEndsAWaitForInput) {
  TempDir dir;
  const GroupRun run = beside_cpu_hog([&] {
    return run_program(dir, {TIMESHIM_PROBE, "fd_wakes"}, deterministic_in(dir));
  });
  ASSERT_EQ(run.exit_status, 0) << run.output;
  EXPECT_GT(run.light_looks, 0U);
  for (const char* kind : {"write", "send", "stdio", "close"}) {
    const std::string label = std::string(kind) + "_lag_max";
    EXPECT_LT(value_of(run.seen, label), 0.0005) << label << "\n" << run.output;
  }
  EXPECT_TRUE(blocking_problems(run).empty()) << all_text(run.problems);
}

TEST(Timeshim, DeterministicModeNamesAThreadThatBlocksHoldingTheTokenAndGoesOn) {
  TempDir dir;
  ControllerOptions options = deterministic_in(dir);
  options.grace = std::chrono::milliseconds(300);
  Controller group(options);
  const std::string output = dir.path("output.txt");
  const pid_t pid = group.spawn({TIMESHIM_PROBE, "raw_futex_wait"}, output);
  // The main thread waits in a raw futex for a thread that cannot run.
  std::vector<Problem> problems;
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (problems.empty() && std::chrono::steady_clock::now() < give_up) {
    group.run_until(kNoDeadline, std::chrono::milliseconds(200));
    problems = group.take_problems();
  }
  ASSERT_EQ(problems.size(), 1U) << all_text(problems);
  EXPECT_NE(
      problems[0].text.find("holds the deterministic mode's run token while blocked in futex"),
      std::string::npos)
      << problems[0].text;
  EXPECT_NE(problems[0].text.find("timeshim_probe"), std::string::npos) << problems[0].text;
  EXPECT_EQ(problems[0].tid, problems[0].pid);  // the main thread
  // Named, the token is taken from it: the other thread runs, and the program ends.
  const GroupRun run = run_to_end(group, pid, output);
  EXPECT_EQ(run.exit_status, 0) << run.output;
  EXPECT_DOUBLE_EQ(value_of(run.seen, "end"), 0.0);
}

TEST(Timeshim, RunnerRunsACommandOnSimTime) {
  TempDir dir;
  const std::string log = dir.path("runner.log");
  ubersim::test::ChildProcess runner({TIMESHIM_RUN, "-v", "--", TIMESHIM_PROBE, "sleeps"}, log);
  EXPECT_EQ(runner.wait(60), 0) << read_file(log);
  const std::string text = read_file(log);
  EXPECT_NE(text.find("sleep_for 8.000000000"), std::string::npos) << text;
  EXPECT_NE(text.find("timeshim: sim time 8.000000 s"), std::string::npos) << text;
}

TEST(Timeshim, GroupEndsWhenItsControllerIsGone) {
  TempDir dir;
  const std::string log = dir.path("runner.log");
  ubersim::test::ChildProcess runner({TIMESHIM_RUN, "--", TIMESHIM_PROBE, "socket_wait"}, log);
  // The probe waits for input with no deadline, for ever.
  pid_t probe = 0;
  for (int i = 0; i < 500 && probe == 0; ++i) {
    std::istringstream(read_file("/proc/" + std::to_string(runner.pid()) + "/task/" +
                                 std::to_string(runner.pid()) + "/children")) >>
        probe;
    if (probe == 0) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_NE(probe, 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_EQ(runner.stop(10, SIGKILL), 128 + SIGKILL);
  // Its shim waits check once a second of wall time that the controller runs.
  bool gone = false;
  for (int i = 0; i < 100 && !gone; ++i) {
    gone = !ubersim::test::process_alive(probe);
    if (!gone) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  EXPECT_TRUE(gone);
  EXPECT_NE(
      read_file(log).find("the controller (pid " + std::to_string(runner.pid()) + ") is gone"),
      std::string::npos)
      << read_file(log);
}

TEST(Timeshim, RunnerRejectsABadCommandLine) {
  TempDir dir;
  const std::string log = dir.path("runner.log");
  ubersim::test::ChildProcess runner({TIMESHIM_RUN, "--charge-us", "-3", "--", "true"}, log);
  EXPECT_EQ(runner.wait(20), 2) << read_file(log);
}

}  // namespace
}  // namespace ubersim::timeshim
