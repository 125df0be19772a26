#include "ubersim/physics/physics_pacing.hpp"

#include <algorithm>
#include <cmath>

namespace ubersim::physics {
namespace {

using namespace std::chrono_literals;
using Clock = PacingClock;

// How long a wait lasts at most while physics is held before its start, at
// the horizon and at the end of a sync run: the hooks and timers run at least
// this often (the host also ends a wait at its next timer).
constexpr auto kHeldWait = 100ms;
// How often the state physics waits at goes out again for the vision: one
// that started listening after it went out never saw it.
constexpr auto kVisionRepeat = 100ms;
// The longest wait for the vision's acknowledgement when its schedules do not
// wake physics (started in real time, switched to as fast as possible).
constexpr auto kVisionLook = 1ms;
// Sync mode, the run's duration reached: how long physics waits for the
// answers to the last frames.
constexpr auto kLastAnswersWait = 3s;

}  // namespace

std::string horizon_bound_name(const PhysicsCore::HorizonBound& bound) {
  switch (bound.by) {
    case PhysicsCore::HorizonBound::By::NoHorizonYet:
      return "the radio emulator (no SIM_SYNC_HORIZON yet)";
    case PhysicsCore::HorizonBound::By::Registration:
      return "the sync clients' registration";
    case PhysicsCore::HorizonBound::By::Referee:
      return "referee";
    case PhysicsCore::HorizonBound::By::Horizon:
      break;
  }
  // Whom the radio emulator says it waits for: a client's name or "vision".
  return bound.waiting_for.empty() ? "?" : bound.waiting_for;
}

void LongWaitNote::waiting(Clock::time_point now, double sim_time, const std::string& whom) {
  if (!since_ || whom != whom_) {
    since_ = now;
    whom_ = whom;
    said_ = false;
    return;
  }
  if (said_ || now - *since_ < kAfter) return;
  said_ = true;
  spdlog::warn("sync: physics waits at sim time {:.3f} s for {} ({:.1f} s of wall time so far)",
               sim_time, whom, std::chrono::duration<double>(now - *since_).count());
}

void HeldWait::settle(Clock::time_point now) {
  if (!waiting_since_) return;
  *seconds_ += std::chrono::duration<double>(now - *waiting_since_).count();
  ++*waits_;
  waiting_since_.reset();
}

Turn HeldWait::wait(Clock::time_point now, Clock::time_point until, double& seconds,
                    std::int64_t& waits) {
  waiting_since_ = now;
  seconds_ = &seconds;
  waits_ = &waits;
  return Turn::wait_until(until);
}

Turn IdleWait::turn(Clock::time_point now) {
  // Only a message (RESUME, STEP, a speed ...) makes physics step; the host
  // ends the wait for its timers (the geometry, the state late joiners see).
  return Turn::wait_until(now + std::chrono::hours(1));
}

void StartGate::on_sync_horizon(const sync_horizon_t& horizon) {
  if (std::isnan(horizon.horizon)) return;
  // Until its clients registered, the radio emulator holds the start.
  radio_ready_ = horizon.held_by != sync_horizon_t::HELD_BY_REGISTRATION;
}

bool StartGate::open() const {
  return vision_.heard() && (radio_ready_ || !loop_.core.sync());
}

void StartGate::start_now() {
  loop_.publisher.publish(loop_.core.state());
  started_ = true;
}

Turn StartGate::turn(Clock::time_point now) {
  if (!open()) {
    long_wait_.waiting(
        now, loop_.core.world().time(),
        vision_.heard() ? "the sync clients' registration (SYNC_CLIENT)" : "the vision emulator");
    return Turn::wait_until(now + kHeldWait);
  }
  loop_.publisher.publish(loop_.core.state());
  started_ = true;
  first_state_wall_ = now;
  return Turn::again();
}

Turn SyncSteps::turn(Clock::time_point now) {
  PhysicsCore& core = loop_.core;
  if (!core.below_horizon()) {
    // What is already waiting may move the horizon: no system call to sleep then.
    if (!loop_.hold.looked()) return loop_.hold.look();
    const std::string bound = horizon_bound_name(core.horizon_bound());
    long_wait_.waiting(now, core.world().time(), bound);
    return loop_.hold.wait(now, now + kHeldWait, loop_.stats.sync_wait_seconds[bound],
                           loop_.stats.sync_waits[bound]);
  }
  if (loop_.poll.due(now)) return Turn::poll();
  loop_.hold.released();
  long_wait_.released();
  loop_.publisher.publish(core.step());
  return Turn::again();
}

Turn AsFastAsPossible::turn(Clock::time_point now) {
  if (loop_.poll.due(now)) return Turn::poll();
  const World& world = loop_.core.world();
  if (vision_.holds(world.time(), world.dt(), now)) return wait_for_vision(now);
  wait_began_.reset();
  loop_.hold.released();
  loop_.publisher.publish(loop_.core.step());
  return Turn::again();
}

Turn AsFastAsPossible::wait_for_vision(Clock::time_point now) {
  // The step physics waits at: its state goes out (if no demand sent it) for
  // the vision to acknowledge, and again every kVisionRepeat.
  const bool again = wait_began_ && now - *wait_began_ >= kVisionRepeat;
  if (!wait_began_ || again) {
    wait_began_ = now;
    const PhysicsCore::Output& out = loop_.core.state_to_acknowledge(again);
    loop_.stats.states_for_vision += static_cast<std::int64_t>(out.states.size());
    loop_.publisher.publish(out);
  }
  // What is already waiting may be the acknowledgement: no sleep then.
  if (!loop_.hold.looked()) return loop_.hold.look();
  const auto longest = schedule_wakes_ ? kVisionRepeat : kVisionLook;
  return loop_.hold.wait(now, std::min(*wait_began_ + kVisionRepeat, now + longest),
                         loop_.stats.vision_wait_seconds, loop_.stats.vision_waits);
}

PacedSteps::PacedSteps(StepLoop& loop, double max_pacing_lag)
    : loop_(loop),
      pacer_(loop.core.world().dt(), loop.core.speed(), max_pacing_lag),
      schedule_epoch_(loop.core.schedule_epoch()) {}

void PacedSteps::start(Clock::time_point now) {
  schedule_epoch_ = loop_.core.schedule_epoch();
  pacer_.set_speed(loop_.core.speed(), now, loop_.core.world().step_index());
}

void PacedSteps::follow_core(Clock::time_point now) {
  if (loop_.core.schedule_epoch() != schedule_epoch_) start(now);
}

double PacedSteps::drift(Clock::time_point now) {
  follow_core(now);
  return pacer_.drift(now, loop_.core.world().step_index());
}

Turn PacedSteps::turn(Clock::time_point now) {
  follow_core(now);
  PhysicsCore& core = loop_.core;
  const std::int64_t step = core.world().step_index();
  const auto due = pacer_.due(step);
  if (now < due) {
    loop_.stepping_clock.run_ends();
    return Turn::wait_until(wake_for(due));
  }
  if (pacer_.restart_if_behind(now, step)) {
    ++loop_.stats.schedule_restarts;
    core.warnings().warn("pacing",
                         "physics cannot keep up with the requested speed: schedule restarted");
  }
  // Measured only where steps are few (paced), per run of steps.
  loop_.stepping_clock.step_begins();
  const PhysicsCore::Output& out = core.step();
  if (!out.states.empty()) loop_.stepping_clock.run_ends();  // publishing comes next
  loop_.publisher.publish(out);
  return Turn::again();
}

Clock::time_point PacedSteps::wake_for(Clock::time_point due) const {
  // A command waits in the world until its t_apply whenever it arrived (and
  // is read at the latest when this wait ends), and any other message still
  // wakes physics at once (a new demand may want an earlier state), so only
  // the wall time at which unseen steps run changes. At most 50 ms of steps
  // at once, well within the pacing lag.
  const World& world = loop_.core.world();
  const double window = std::min(0.05, world.setup().physics.max_pacing_lag / 2);
  const auto max_steps =
      std::max<std::int64_t>(1, static_cast<std::int64_t>(window * pacer_.speed() / world.dt()));
  const std::int64_t k = loop_.core.steps_to_wanted_state(max_steps);
  return k <= 1 ? due : pacer_.due(world.step_index() + k - 1);
}

Turn LastAnswers::turn(Clock::time_point now) {
  if (!deadline_) deadline_ = now + kLastAnswersWait;
  if (loop_.core.last_frames_answered()) return Turn::finish();
  if (now >= *deadline_) {
    spdlog::warn("sync: the run ends without the answers to the last frames (answered until {} s)",
                 loop_.core.answered_until());
    return Turn::finish();
  }
  return Turn::poll_then_wait_until(std::min(*deadline_, now + kHeldWait));
}

PhysicsPacing::PhysicsPacing(PhysicsCore& core, OutputPublisher& publisher, ServerStats& stats,
                             SteppingClock& stepping_clock, const PacingOptions& options)
    : loop_(core, publisher, stats, stepping_clock, options.poll_period),
      gate_(loop_, vision_),
      sync_(loop_),
      fast_(loop_, vision_, options.schedule_wakes),
      paced_(loop_, options.max_pacing_lag),
      last_answers_(loop_) {}

void PhysicsPacing::start(Clock::time_point now, bool gated) {
  if (!gated) gate_.start_now();
  paced_.start(now);
}

void PhysicsPacing::finish(Clock::time_point now) {
  loop_.hold.settle(now);
  loop_.stepping_clock.run_ends();
}

Turn PhysicsPacing::ending(Clock::time_point now) {
  if (loop_.core.sync() && gate_.started()) return last_answers_.turn(now);
  return Turn::finish();
}

}  // namespace ubersim::physics
