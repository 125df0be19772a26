#pragma once
// The process host: what every ubersim program has around its core, in one
// place (docs/design.md, "The process host"). A program is its core plus its
// shell (PhysicsShell, VisionShell, ViewerShell ...), which hands the host
// what the core needs:
//
//   ProcessHost host(options.common, "viewer");
//   subscribe(host.bus(), host.channels(), topics::kSimState,
//             [&](const sim_state_t& m) { model.on_sim_state(m, host.now()); });
//   host.every(frame_period, [&](ProcessHost::Clock::time_point now) { ... });
//   host.ask_for_truth(periodic_demand(60));
//   return host.run();
//
// The host owns the bus, the shutdown signal, the wait loop, the wall clock
// (now(): cores get time passed in, they never read a clock), timers for the
// repeats (geometry, schedules, display frames), the truth-demand announcer,
// the status of what the bus dropped, and the clean stop (at_stop hooks run
// once, on SIGINT/SIGTERM, stop() or when a pacing policy says the run is over).
//
// How the loop goes between its waits is a small policy (Pacing): a program
// that only reacts to messages waits (the default, WaitForMessages); physics
// gives the host one that steps (paced to the wall clock, as fast as
// possible, up to a sync horizon ...).
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ubersim/channels.hpp"
#include "ubersim/message_bus.hpp"
#include "ubersim/shutdown.hpp"
#include "ubersim/truth_demand_announcer.hpp"

namespace ubersim {

struct CommonOptions;

// What the loop does next, as one turn of a pacing policy says.
struct Turn {
  using Clock = std::chrono::steady_clock;
  enum class Kind {
    Wait,          // wait for messages until `until` (or the next timer), handling them
    PollThenWait,  // handle what already waits; only if nothing did, wait as Wait
    Poll,          // handle what already waits, no wait
    Again,         // no bus call: the next turn at once (the policy did work)
    Finish,        // the run is over: stop cleanly with status 0
  };
  Kind kind = Kind::Wait;
  Clock::time_point until{};

  static Turn wait_until(Clock::time_point t) { return {Kind::Wait, t}; }
  static Turn poll_then_wait_until(Clock::time_point t) { return {Kind::PollThenWait, t}; }
  static Turn poll() { return {Kind::Poll, {}}; }
  static Turn again() { return {Kind::Again, {}}; }
  static Turn finish() { return {Kind::Finish, {}}; }
};

// How a program's loop goes between its waits: asked once per turn, after the
// host ran its hooks and timers; does the work that is due (a step) and says
// what the loop does next.
class Pacing {
 public:
  using Clock = Turn::Clock;
  virtual ~Pacing() = default;
  virtual Turn turn(Clock::time_point now) = 0;
};

// The policy of every program that only reacts: wait for messages, at most
// `max_wait` at a time (the hooks run after each wait).
class WaitForMessages final : public Pacing {
 public:
  explicit WaitForMessages(Clock::duration max_wait) : max_wait_(max_wait) {}
  Turn turn(Clock::time_point now) override { return Turn::wait_until(now + max_wait_); }

 private:
  Clock::duration max_wait_;
};

class ProcessHost {
 public:
  using Clock = Turn::Clock;
  using Tick = std::function<void(Clock::time_point now)>;

  // A repeat: runs when due, then again `period` later. FromLastRun counts
  // the period from when it ran (a repeat that only keeps something alive);
  // FixedRate keeps to its grid and, when it fell behind, skips what it missed
  // rather than catching up (a display rate).
  class Timer {
   public:
    enum class Rate { FromLastRun, FixedRate };
    Clock::time_point due() const { return due_; }
    // The next run at `t` (e.g. now, or one period after an out-of-turn run).
    void due_at(Clock::time_point t) { due_ = t; }
    Clock::duration period() const { return period_; }

   private:
    friend class ProcessHost;
    Timer(Clock::duration period, Rate rate, Tick tick, Clock::time_point due)
        : period_(period), rate_(rate), tick_(std::move(tick)), due_(due) {}
    void run(Clock::time_point now);
    Clock::duration period_;
    Rate rate_;
    Tick tick_;
    Clock::time_point due_;
  };

  // Opens the bus on `lcm_url` and installs the shutdown signal (one host per
  // process). `name` is who the program is to others: the consumer of its
  // truth demand. Throws std::runtime_error when LCM cannot open the URL.
  ProcessHost(const std::string& lcm_url, ChannelNames channels, std::string name);
  // The program's command line: its URL with the receive buffer every
  // process asks for, its channel names.
  ProcessHost(const CommonOptions& common, std::string name);
  ProcessHost(const ProcessHost&) = delete;
  ProcessHost& operator=(const ProcessHost&) = delete;

  MessageBus& bus() { return bus_; }
  const ChannelNames& channels() const { return channels_; }
  const std::string& name() const { return name_; }
  // The one wall clock of the program. Cores are handed what it says.
  Clock::time_point now() const { return Clock::now(); }

  // A repeat, first due one period from now (Timer::due_at moves it).
  Timer& every(Clock::duration period, Tick tick, Timer::Rate rate = Timer::Rate::FromLastRun);
  // Runs at the start of every turn of the loop, i.e. after every wakeup
  // (and once before the first wait), in the order they were added.
  void after_wake(Tick hook);
  // Runs once when the run stops cleanly, in the order they were added
  // (say goodbye, log a summary).
  void at_stop(std::function<void()> hook);

  // What this program needs of ground truth (docs/sync.md, "Ground truth on
  // demand"), the one way to say it: `demand` says it whenever asked (after
  // every wakeup, after the hooks added before the first call). The host
  // sends it on SIM_TRUTH_DEMAND before the first wait, whenever it differs
  // from what went out last, and at least once a second. A program that
  // asks nothing never calls this (physics then publishes every step).
  void ask_for_truth(TruthDemandAnnouncer::Source demand);
  // A demand that never changes (every_step_demand(), periodic_demand()).
  void ask_for_truth(const truth_demand_t& fixed);
  // Sends the demand at once, changed or not (nothing when none was asked
  // for): before something that lets physics step in sync mode (a
  // registration, the first schedule), which must know it by then.
  void send_truth_demand(Clock::time_point now);
  // Sends the demand if it changed or a second has passed, as the wait loop
  // does: for a program whose own work keeps it out of that loop for longer
  // (the SSL bridge running its team programs), lest physics forget it.
  void renew_truth_demand(Clock::time_point now);

  // Ends run() after the current turn with `status` (a fatal condition: 1).
  void stop(int status);
  bool stopping() const { return stop_status_.has_value() || shutdown_.requested(); }
  const ShutdownSignal& shutdown() const { return shutdown_; }

  // The status line of what the bus dropped, per kind and channel (for a
  // status reply such as physics' PING).
  std::string dropped_input() const { return bus_.bad_input().counts(); }

  // Runs the loop until a signal, stop() or the pacing's Finish; then the
  // at_stop hooks. Returns the exit status (0 for a clean stop).
  int run(Pacing& pacing);
  // The reacting programs' loop: WaitForMessages(max_wait).
  int run(Clock::duration max_wait = std::chrono::milliseconds(500));

 private:
  void run_hooks(Clock::time_point now);
  void run_due_timers(Clock::time_point now);
  Clock::time_point next_timer(Clock::time_point otherwise) const;
  // Carries out one turn's bus work; false when the run is over.
  bool carry_out(const Turn& turn);

  ShutdownSignal shutdown_;
  MessageBus bus_;
  ChannelNames channels_;
  std::string name_;
  std::vector<std::unique_ptr<Timer>> timers_;
  std::vector<Tick> hooks_;
  std::vector<std::function<void()>> stop_hooks_;
  std::unique_ptr<TruthDemandAnnouncer> truth_demand_;
  std::optional<int> stop_status_;
};

}  // namespace ubersim
