#pragma once
// How physics' loop goes between its waits, as Pacing policies for the
// process host (process_host.hpp): one small policy per mode, and
// PhysicsPacing, which picks one at each turn, because SIM_CONTROL switches
// pause, speed and sync at run time.
//
//   the run's end reached       LastAnswers       sync: until the last frames' answers are in
//   paused, lockstep            IdleWait          wait for messages (the host's timers run)
//   before the first state      StartGate         sync, --wait-for-vision: until the others listen
//   sync                        SyncSteps         step up to the horizon, then wait for the next
//   as fast as possible         AsFastAsPossible  step back to back, within the vision's lead
//   real time, speed factor     PacedSteps        step when the Pacer says it is due
//
// The policies get the wall time from the host (turn(now)) and hand it on:
// the core reads no clock. A step turn makes no bus call and no std::function
// call (Turn::again()); the step loops look at the bus once per
// MESSAGE_POLL_PERIOD, so a step costs no system call beyond its publication.
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <ubersim/sync_horizon_t.hpp>
#include <ubersim/vision_schedule_t.hpp>

#include "ubersim/physics/output_publisher.hpp"
#include "ubersim/physics/pacer.hpp"
#include "ubersim/physics/physics_core.hpp"
#include "ubersim/physics/server_stats.hpp"
#include "ubersim/physics/stepping_clock.hpp"
#include "ubersim/physics/vision_lead.hpp"
#include "ubersim/process_host.hpp"

namespace ubersim::physics {

using PacingClock = Pacing::Clock;

// What holds physics at the horizon, named for its log ("sync: waited ... for NAME").
std::string horizon_bound_name(const PhysicsCore::HorizonBound& bound);

// Sync and as fast as possible: looking for messages costs system calls; at
// tens of thousands of steps a second, look every `period` of wall time
// (MESSAGE_POLL_PERIOD) instead of every step.
class PollSchedule {
 public:
  explicit PollSchedule(PacingClock::duration period) : period_(period) {}
  // True, and the next look scheduled, when it is time to look.
  bool due(PacingClock::time_point now) {
    if (now < next_) return false;
    next_ = now + period_;
    return true;
  }

 private:
  PacingClock::duration period_;
  PacingClock::time_point next_{};
};

// Physics held (at the horizon, or by the vision's lead): first it handles
// what already waits on the bus, which may release it, without a system call
// to sleep; then it waits, and each wait is counted with its wall time in
// ServerStats, until a step runs.
class HeldWait {
 public:
  // At the start of every turn: the wait the last turn began, counted.
  void settle(PacingClock::time_point now);
  // Held: whether the bus was looked at since the last step.
  bool looked() const { return looked_; }
  // Held, first: what already waits on the bus.
  Turn look() {
    looked_ = true;
    return Turn::poll();
  }
  // Held, then: a wait until `until`, counted in `seconds` and `waits`.
  Turn wait(PacingClock::time_point now, PacingClock::time_point until, double& seconds,
            std::int64_t& waits);
  // A step ran: the next hold looks at the bus first again.
  void released() { looked_ = false; }

 private:
  bool looked_ = false;
  std::optional<PacingClock::time_point> waiting_since_;
  double* seconds_ = nullptr;
  std::int64_t* waits_ = nullptr;
};

// What every mode's policy works on: the core, where its output goes, and the
// loop's own figures.
struct StepLoop {
  StepLoop(PhysicsCore& the_core, OutputPublisher& its_publisher, ServerStats& its_stats,
           SteppingClock& its_stepping_clock, PacingClock::duration poll_period)
      : core(the_core),
        publisher(its_publisher),
        stats(its_stats),
        stepping_clock(its_stepping_clock),
        poll(poll_period) {}
  PhysicsCore& core;
  OutputPublisher& publisher;
  ServerStats& stats;
  SteppingClock& stepping_clock;  // CPU time of the paced steps
  PollSchedule poll;
  HeldWait hold;
};

// Paused, or lockstep outside sync mode: nothing advances by itself.
class IdleWait final : public Pacing {
 public:
  Turn turn(PacingClock::time_point now) override;
};

// Sync mode and --wait-for-vision publish the first state, and step, only once
// the others are ready, so that every run starts alike: a vision emulator
// listens (it has sent SIM_VISION_SCHEDULE) and, in sync mode, the radio
// emulator has every client it expects (its horizon is no longer held by
// HELD_BY_REGISTRATION).
// Sync mode: one log line when physics has waited longer than kAfter of wall
// time in one place (tools/launch.sh shows it on the terminal: docs/sync.md).
class LongWaitNote {
 public:
  static constexpr std::chrono::seconds kAfter{2};
  // Physics waits at sim_time for `whom`; logs once per wait past kAfter.
  void waiting(PacingClock::time_point now, double sim_time, const std::string& whom);
  void released() { since_.reset(); }

 private:
  std::optional<PacingClock::time_point> since_;
  std::string whom_;
  bool said_ = false;
};

class StartGate final : public Pacing {
 public:
  StartGate(StepLoop& loop, const VisionLead& vision) : loop_(loop), vision_(vision) {}
  void on_sync_horizon(const sync_horizon_t& horizon);
  // Started without waiting for anyone: the first state goes out now.
  void start_now();
  bool started() const { return started_; }
  // When the first state went out through the gate (not set by start_now).
  std::optional<PacingClock::time_point> first_state_wall() const { return first_state_wall_; }
  Turn turn(PacingClock::time_point now) override;

 private:
  bool open() const;
  StepLoop& loop_;
  const VisionLead& vision_;
  bool radio_ready_ = false;
  bool started_ = false;
  std::optional<PacingClock::time_point> first_state_wall_;
  LongWaitNote long_wait_;
};

// Sync mode: as fast as possible below the horizon, looking for messages (a
// further horizon among them) every MESSAGE_POLL_PERIOD; at it, waiting for
// the next (docs/sync.md).
class SyncSteps final : public Pacing {
 public:
  explicit SyncSteps(StepLoop& loop) : loop_(loop) {}
  Turn turn(PacingClock::time_point now) override;

 private:
  StepLoop& loop_;
  LongWaitNote long_wait_;
};

// As fast as possible: steps back to back, looking for messages every
// MESSAGE_POLL_PERIOD; once a vision emulator listens, at most kVisionLead
// ahead of the last state it acknowledged (docs/vision.md).
class AsFastAsPossible final : public Pacing {
 public:
  // `schedule_wakes`: the vision's schedules wake physics; otherwise it looks
  // for them every millisecond while it waits.
  AsFastAsPossible(StepLoop& loop, VisionLead& vision, bool schedule_wakes)
      : loop_(loop), vision_(vision), schedule_wakes_(schedule_wakes) {}
  Turn turn(PacingClock::time_point now) override;

 private:
  // One turn of waiting for the vision's acknowledgement.
  Turn wait_for_vision(PacingClock::time_point now);
  StepLoop& loop_;
  VisionLead& vision_;
  bool schedule_wakes_;
  // When physics began to wait for the vision at the current step.
  std::optional<PacingClock::time_point> wait_began_;
};

// Real time and speed factors: a step runs when the Pacer's absolute schedule
// says it is due; the schedule restarts when the core says (resume, reset,
// step requests, speed changes) and when physics cannot keep up.
class PacedSteps final : public Pacing {
 public:
  PacedSteps(StepLoop& loop, double max_pacing_lag);
  // The schedule starts at `now` from the current step.
  void start(PacingClock::time_point now);
  // Sim time ahead of the schedule at `now` (s).
  double drift(PacingClock::time_point now);
  Turn turn(PacingClock::time_point now) override;

 private:
  // Restarts the schedule at `now` when the core asked for it since the last turn.
  void follow_core(PacingClock::time_point now);
  // When to wake for the step due at `due`. With states on demand, the steps
  // before the next wanted state run when that one is due (docs/sync.md,
  // "Steps nobody sees"), instead of one wakeup a step.
  PacingClock::time_point wake_for(PacingClock::time_point due) const;
  StepLoop& loop_;
  Pacer pacer_;
  std::uint64_t schedule_epoch_;
};

// Sync mode, the run's duration reached: the run ends when physics exits, and
// the launch script then stops every process, so it waits until the clients'
// answers to the frames published up to the last state are in (the horizon
// says so), so that every run's log ends alike. At most 3 s: a client that
// never answers is dropped after its timeout, which also ends this wait.
class LastAnswers final : public Pacing {
 public:
  explicit LastAnswers(StepLoop& loop) : loop_(loop) {}
  Turn turn(PacingClock::time_point now) override;

 private:
  StepLoop& loop_;
  std::optional<PacingClock::time_point> deadline_;
};

struct PacingOptions {
  PacingClock::duration poll_period{};  // MESSAGE_POLL_PERIOD
  double max_pacing_lag = 0.25;         // s, MAX_PACING_LAG
  bool schedule_wakes = false;          // SIM_VISION_SCHEDULE wakes physics
};

// The policy physics gives the host: each turn, the one its mode calls for.
class PhysicsPacing final : public Pacing {
 public:
  PhysicsPacing(PhysicsCore& core, OutputPublisher& publisher, ServerStats& stats,
                SteppingClock& stepping_clock, const PacingOptions& options);

  void on_vision_schedule(const vision_schedule_t& schedule, PacingClock::time_point wall) {
    vision_.on_schedule(schedule, wall);
  }
  void on_sync_horizon(const sync_horizon_t& horizon) { gate_.on_sync_horizon(horizon); }
  // At the start of the run: the real-time schedule starts at `now`; the
  // first state goes out now unless `gated` (sync, --wait-for-vision).
  void start(PacingClock::time_point now, bool gated);

  Turn turn(PacingClock::time_point now) override {
    loop_.hold.settle(now);
    PhysicsCore& core = loop_.core;
    if (core.duration_reached()) return ending(now);
    if (core.idle()) return idle_.turn(now);
    if (!gate_.started()) return gate_.turn(now);
    if (core.sync()) return sync_.turn(now);
    if (core.as_fast_as_possible()) return fast_.turn(now);
    return paced_.turn(now);
  }

  const StartGate& gate() const { return gate_; }
  const VisionLead& vision() const { return vision_; }
  double drift(PacingClock::time_point now) { return paced_.drift(now); }
  // The run stopped at `now`: the last wait counted, the last run of steps measured.
  void finish(PacingClock::time_point now);

 private:
  Turn ending(PacingClock::time_point now);
  StepLoop loop_;
  VisionLead vision_;
  IdleWait idle_;
  StartGate gate_;
  SyncSteps sync_;
  AsFastAsPossible fast_;
  PacedSteps paced_;
  LastAnswers last_answers_;
};

}  // namespace ubersim::physics
