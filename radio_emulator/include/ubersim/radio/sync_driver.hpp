#pragma once
// Sync mode in the radio emulator process (docs/sync.md): joins the
// SyncCoordinator and the emulator's links. The program's shell
// (RadioShell, radio_shell.cpp) hands it what comes on SYNC_CLIENT and SIM_VISION_SCHEDULE and the
// teams' radio packets, which it takes as answers, and calls tick() after every
// wakeup; it publishes on SIM_SYNC_HORIZON how far physics may step: the
// earliest t_apply any command not yet forwarded can still get. Each client it
// drops, and each that rejoins, is one log line and goes out on
// SIM_SYNC_STATUS (docs/sync.md, "A dropped client"). It reads no clock: the
// wall time of each call is an argument (the process host's clock).
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <ubersim/sync_client_t.hpp>
#include <ubersim/sync_horizon_t.hpp>
#include <ubersim/sync_status_t.hpp>
#include <ubersim/vision_schedule_t.hpp>
#include <vector>

#include "ubersim/channels.hpp"
#include "ubersim/logging.hpp"
#include "ubersim/message_bus.hpp"
#include "ubersim/radio/radio_emulator.hpp"
#include "ubersim/radio/sync_coordinator.hpp"
#include "ubersim/topics.hpp"

namespace ubersim::radio {

struct SyncOptions {
  double client_timeout = 1.0;  // s of wall time a client may take to answer a frame
  bool strict = false;          // a client timing out fails the run
  int expected_clients = 0;     // physics holds at the start until this many registered
};

class SyncDriver {
 public:
  using Clock = SyncCoordinator::Clock;
  // `publish` sends what the emulator's links let through (main.cpp's, the
  // same as outside sync mode), before the horizon that lets physics past it.
  using Publish = std::function<void(const RadioEmulator::Output&)>;
  SyncDriver(MessageBus& bus, const ChannelNames& channels, RadioEmulator& emulator,
             SyncOptions options, Publish publish);

  // A registration or goodbye on SYNC_CLIENT.
  void on_client(const sync_client_t& message, Clock::time_point now);
  // The frames announced on SIM_VISION_SCHEDULE.
  void on_schedule(const vision_schedule_t& schedule, Clock::time_point now);
  // A packet on RADIO_<team>: an answer, if the team has a client.
  void on_packet(Team team, const radio_packet_t& packet, Clock::time_point now);
  // A SIM_STATE: the emulator's input, then the answers held for the first one.
  void on_sim_state(const sim_state_t& state, Clock::time_point now);
  // Every wakeup (at least every 50 ms): drops clients past the timeout.
  // False when that fails the run (strict).
  bool tick(Clock::time_point now);
  void log_summary() const;
  // Runs once, right before the first horizon that lets physics start (every
  // expected client registered): the radio's truth demand must reach physics
  // before its first step, or the feedback instants it names come late and a
  // rerun publishes other states.
  void before_release(std::function<void()> hook) { before_release_ = std::move(hook); }
  // Runs before every horizon it publishes: the radio's truth demand, if it
  // changed, goes first, so that physics knows the states it must publish
  // (a feedback delivery) before it may step to them.
  void before_horizon(std::function<void(Clock::time_point)> hook) {
    before_horizon_ = std::move(hook);
  }

  // A wakeup later than this after the previous one means this process did
  // not run (the machine was loaded or paused): the gap does not count
  // against the clients, who could not run either.
  static constexpr auto kStall = std::chrono::milliseconds(250);
  // The horizon is said again at least this often: physics waits for a first
  // word from the radio emulator before it starts.
  static constexpr auto kHorizonRepeat = std::chrono::milliseconds(100);
  static constexpr auto kStatusRepeat = std::chrono::seconds(1);
  // Answers held before physics' first state: a client's start-up packets
  // (sent at sim time 0) may come before it on another socket. Beyond this
  // many the newest are dropped, counted and logged.
  static constexpr std::size_t kMaxHeldAnswers = 256;

 private:
  void clients_changed();  // a client joined, left or was dropped
  void update(bool always_publish, Clock::time_point now);
  // Why physics holds at the start (the horizon 0): registration or the first frame.
  std::int8_t hold(Clock::time_point now);
  void forgive_own_stall(Clock::time_point now);
  void publish_status(Clock::time_point now);
  // The earliest sim time a packet of `team` can still arrive at, held ones included.
  double earliest_arrival(Team team) const;

  // An accepted answer that came before the first SIM_STATE: checked and
  // offered when it comes, at the arrival time its acceptance gave it.
  struct HeldAnswer {
    Team team;
    radio_packet_t packet;
    double t_arrival;
  };
  std::vector<HeldAnswer> held_;
  std::uint64_t held_dropped_ = 0;

  std::function<void()> before_release_;
  std::function<void(Clock::time_point)> before_horizon_;
  bool released_ = false;
  Publisher<sync_horizon_t> publish_horizon_;
  Publisher<sync_status_t> publish_status_;
  RadioEmulator& emulator_;
  SyncOptions options_;
  Publish publish_;
  SyncCoordinator coordinator_;
  bool started_ = false;  // the expected clients registered once
  sync_horizon_t horizon_{};
  ThrottledLog log_;
  Clock::time_point next_hold_log_{};
  Clock::time_point last_published_{};
  sync_status_t status_{};
  Clock::time_point last_status_{};
  Clock::time_point last_tick_{};
  std::uint64_t stalls_ = 0;
  double stalled_seconds_ = 0;
};

}  // namespace ubersim::radio
