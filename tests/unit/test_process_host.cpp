// The process host over real LCM (UDP multicast, run through run_isolated.sh):
// its loop, timers, hooks, pacing turns, truth demand and clean stop, with a
// second bus in the same process standing for the other programs.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <string>
#include <thread>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/truth_demand_t.hpp>
#include <vector>

#include "ubersim/common_options.hpp"
#include "ubersim/process_host.hpp"
#include "ubersim/topics.hpp"

namespace {

using ubersim::Pacing;
using ubersim::ProcessHost;
using ubersim::Turn;
using Clock = ProcessHost::Clock;
using namespace std::chrono_literals;

// Longer than any test takes when it passes: a wait it must not sit out (a
// broken host fails the test after it, rather than hanging).
constexpr auto kLongWait = 20s;

std::string bus_url() {
  return ubersim::with_receive_buffer(ubersim::default_lcm_url());
}

// A pacing policy made of a function, for the tests' own loops.
class PacingOf final : public Pacing {
 public:
  explicit PacingOf(std::function<Turn(Clock::time_point)> turn) : turn_(std::move(turn)) {}
  Turn turn(Clock::time_point now) override { return turn_(now); }

 private:
  std::function<Turn(Clock::time_point)> turn_;
};

// Collects what arrives on one channel of another bus (another program).
class Listener {
 public:
  explicit Listener(const std::string& channel) : bus_(bus_url()) {
    bus_.subscribe<ubersim::truth_demand_t>(
        channel, [this](const ubersim::truth_demand_t& d) { demands.push_back(d); });
  }
  // Reads until `count` demands arrived (at most 5 s: then the test fails on the count).
  void read_until(std::size_t count) {
    const auto deadline = Clock::now() + 5s;
    while (demands.size() < count && Clock::now() < deadline) bus_.wait_and_handle(50);
  }
  void read_pending() {
    while (bus_.wait_and_handle(20) > 0) {
    }
  }
  std::vector<ubersim::truth_demand_t> demands;

 private:
  ubersim::MessageBus bus_;
};

TEST(ProcessHost, AMessageWakesTheLoopAndTheHooksSeeIt) {
  ProcessHost host(bus_url(), ubersim::ChannelNames(), "test");
  ubersim::MessageBus other(bus_url());
  std::vector<std::int64_t> handled;
  host.bus().subscribe<ubersim::radio_packet_t>(
      "RADIO_BLUE", [&](const ubersim::radio_packet_t& p) { handled.push_back(p.sequence); });
  int hook_runs_with_message = 0;
  host.after_wake([&](Clock::time_point) {
    if (handled.empty()) {
      ubersim::radio_packet_t packet{};
      packet.sequence = 7;
      other.publish("RADIO_BLUE", packet);
      return;
    }
    ++hook_runs_with_message;
    host.stop(0);
  });
  bool stopped = false;
  host.at_stop([&] { stopped = true; });
  // The loop waits up to kLongWait at a time: only the message can end the wait.
  const auto start = Clock::now();
  EXPECT_EQ(host.run(kLongWait), 0);
  EXPECT_LT(Clock::now() - start, kLongWait);
  EXPECT_EQ(handled, std::vector<std::int64_t>{7});
  EXPECT_EQ(hook_runs_with_message, 1);
  EXPECT_TRUE(stopped);
}

TEST(ProcessHost, TimersRepeatFromTheirLastRunAndEndTheWaitWhenDue) {
  ProcessHost host(bus_url(), ubersim::ChannelNames(), "test");
  std::vector<Clock::time_point> runs;
  host.every(5ms, [&](Clock::time_point now) {
    runs.push_back(now);
    if (runs.size() == 4) host.stop(0);
  });
  const auto start = Clock::now();
  // A long wait is cut short by the next timer each time.
  EXPECT_EQ(host.run(kLongWait), 0);
  ASSERT_EQ(runs.size(), 4u);
  EXPECT_GE(runs[0] - start, 5ms);  // first due one period after it was made
  for (std::size_t i = 1; i < runs.size(); ++i) EXPECT_GE(runs[i] - runs[i - 1], 5ms);
}

TEST(ProcessHost, AFixedRateTimerFallenBehindSkipsRatherThanCatchesUp) {
  ProcessHost host(bus_url(), ubersim::ChannelNames(), "test");
  std::vector<Clock::time_point> runs;
  ProcessHost::Timer& timer = host.every(
      10ms,
      [&](Clock::time_point now) {
        runs.push_back(now);
        if (runs.size() == 1) std::this_thread::sleep_for(50ms);  // falls five periods behind
        if (runs.size() == 3) host.stop(0);
      },
      ProcessHost::Timer::Rate::FixedRate);
  timer.due_at(Clock::now());
  host.run(kLongWait);
  ASSERT_EQ(runs.size(), 3u);
  // Caught up, the second run would follow the first at once (its grid
  // point passed long ago); skipping, it comes a period after the late one.
  EXPECT_GE(runs[2] - runs[1], 10ms);
  EXPECT_GE(runs[1] - runs[0], 50ms);
}

TEST(ProcessHost, PacingTurnsDecideWhenTheBusIsRead) {
  ProcessHost host(bus_url(), ubersim::ChannelNames(), "test");
  ubersim::MessageBus other(bus_url());
  int received = 0;
  host.bus().subscribe<ubersim::radio_packet_t>(
      "RADIO_BLUE", [&](const ubersim::radio_packet_t&) { ++received; });
  ubersim::radio_packet_t packet{};
  other.publish("RADIO_BLUE", packet);
  const auto start = Clock::now();
  int turn = 0;
  std::vector<int> seen;
  PacingOf pacing([&](Clock::time_point now) {
    seen.push_back(received);
    ++turn;
    if (turn < 50) {
      // Work without reading: the message waits. Give the kernel time to
      // have it in the socket before the poll below.
      if (turn == 1) std::this_thread::sleep_for(20ms);
      return Turn::again();
    }
    if (turn == 50) return Turn::poll_then_wait_until(now + kLongWait);
    return Turn::finish();
  });
  EXPECT_EQ(host.run(pacing), 0);
  ASSERT_EQ(seen.size(), 51u);
  EXPECT_EQ(seen[49], 0);  // not read while the policy worked
  EXPECT_EQ(seen[50], 1);  // read at once by the poll, without the long wait
  EXPECT_LT(Clock::now() - start, kLongWait);
}

TEST(ProcessHost, ASignalStopsTheRunCleanlyAndStopSetsTheStatus) {
  {
    ProcessHost host(bus_url(), ubersim::ChannelNames(), "test");
    int stops = 0;
    host.at_stop([&] { ++stops; });
    host.after_wake([](Clock::time_point) { std::raise(SIGTERM); });
    EXPECT_EQ(host.run(kLongWait), 0);
    EXPECT_EQ(stops, 1);
    EXPECT_EQ(host.shutdown().signal_number(), SIGTERM);
  }
  ProcessHost host(bus_url(), ubersim::ChannelNames(), "test");
  host.every(1ms, [&](Clock::time_point) { host.stop(1); });
  EXPECT_EQ(host.run(kLongWait), 1);
}

TEST(ProcessHost, TheTruthDemandGoesOutBeforeTheFirstWaitAndOnceASecond) {
  const ubersim::ChannelNames channels;
  Listener listener(ubersim::channel_name(channels, ubersim::topics::kTruthDemand));
  ProcessHost host(bus_url(), channels, "viewer");
  host.ask_for_truth(ubersim::periodic_demand(60));
  int turns = 0;
  PacingOf pacing([&](Clock::time_point now) {
    if (++turns == 1) return Turn::wait_until(now);  // the first turn: no wait yet
    return Turn::finish();
  });
  host.run(pacing);
  listener.read_until(1);
  ASSERT_EQ(listener.demands.size(), 1u);
  EXPECT_EQ(listener.demands[0].consumer, "viewer");
  ASSERT_EQ(listener.demands[0].period.size(), 1u);
  EXPECT_DOUBLE_EQ(listener.demands[0].period[0], 1.0 / 60);
}

TEST(ProcessHost, ADemandGoesOutWhenItChanges) {
  const ubersim::ChannelNames channels;
  Listener listener(ubersim::channel_name(channels, ubersim::topics::kTruthDemand));
  ProcessHost host(bus_url(), channels, "radio");
  double instant = 0.5;
  host.ask_for_truth([&] {
    ubersim::truth_demand_t d{};
    d.instants = {instant};
    d.num_instants = 1;
    return d;
  });
  int turns = 0;
  PacingOf pacing([&](Clock::time_point now) {
    ++turns;
    if (turns == 3) instant = 0.75;  // changed: goes out at the next wakeup
    if (turns == 5) return Turn::finish();
    return Turn::wait_until(now);
  });
  host.run(pacing);
  listener.read_until(2);
  listener.read_pending();
  // The first at once, then only the change (turns 1..4 all within a second).
  ASSERT_EQ(listener.demands.size(), 2u);
  EXPECT_EQ(listener.demands[0].consumer, "radio");  // the host's name
  EXPECT_DOUBLE_EQ(listener.demands[0].instants.at(0), 0.5);
  EXPECT_DOUBLE_EQ(listener.demands[1].instants.at(0), 0.75);
}

// Before something that lets physics step in sync mode (a registration) a
// program sends its demand at once, changed or not.
TEST(ProcessHost, SendTruthDemandSendsItAtOnceChangedOrNot) {
  const ubersim::ChannelNames channels;
  Listener listener(ubersim::channel_name(channels, ubersim::topics::kTruthDemand));
  ProcessHost host(bus_url(), channels, "vision");
  host.send_truth_demand(host.now());  // nothing asked for yet: nothing goes out
  host.ask_for_truth(ubersim::every_step_demand());
  int turns = 0;
  PacingOf pacing([&](Clock::time_point now) {
    ++turns;
    if (turns == 3) host.send_truth_demand(now);
    if (turns == 5) return Turn::finish();
    return Turn::wait_until(now);
  });
  host.run(pacing);
  listener.read_until(2);
  listener.read_pending();
  ASSERT_EQ(listener.demands.size(), 2u);  // the first tick's and the one sent at turn 3
  EXPECT_TRUE(listener.demands[0].every_step);
  EXPECT_TRUE(listener.demands[1].every_step);
}

}  // namespace
