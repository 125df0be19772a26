// Physics' pacing policies (physics_pacing.hpp) turn by turn, without the
// host's loop: a real PhysicsCore and World, the output on a real bus
// (memq://), and the wall time handed in, so no test depends on how fast the
// machine is.
#include <gtest/gtest.h>

#include <chrono>
#include <ubersim/sim_control_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <ubersim/sync_horizon_t.hpp>
#include <ubersim/truth_demand_t.hpp>
#include <ubersim/vision_schedule_t.hpp>
#include <vector>

#include "physics_test_support.hpp"
#include "ubersim/physics/physics_pacing.hpp"
#include "ubersim/topics.hpp"
#include "ubersim/vision_backpressure.hpp"

namespace ubersim::physics::testing {
namespace {

using namespace std::chrono_literals;
using Clock = PacingClock;
using Kind = Turn::Kind;

const Clock::time_point t0 = Clock::time_point{} + 1h;
constexpr auto kPollPeriod = 200us;

Clock::duration wall(double seconds) {
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
}

// A core, where its output goes, and what came out on the bus.
struct Rig {
  explicit Rig(const CoreOptions& options)
      : core(load_world_setup(kConfigDir, "field2002_5v5", "default"), options),
        publisher(bus, channels),
        loop(core, publisher, stats, stepping_clock, kPollPeriod) {
    subscribe(
        bus, channels, topics::kSimState,
        [this](const sim_state_t& s) { states.push_back(s.step); }, 100000);
  }
  // The steps of the states published so far.
  const std::vector<std::int64_t>& published() {
    bus.handle_pending();
    return states;
  }
  std::int64_t step() const { return core.world().step_index(); }
  double dt() const { return core.world().dt(); }

  MessageBus bus{"memq://"};
  ChannelNames channels;
  PhysicsCore core;
  OutputPublisher publisher;
  ServerStats stats;
  SteppingClock stepping_clock;
  StepLoop loop;
  std::vector<std::int64_t> states;
};

sim_control_t control(std::int32_t action) {
  sim_control_t request{};
  request.sender = "test";
  request.action = static_cast<std::int8_t>(action);
  return request;
}

// A horizon held by a client of that name.
sync_horizon_t horizon(double until, const std::string& waiting_for, double answered_until = 0) {
  sync_horizon_t h{};
  h.horizon = until;
  h.held_by = sync_horizon_t::HELD_BY_CLIENT;
  h.waiting_for = waiting_for;
  h.answered_until = answered_until;
  return h;
}

vision_schedule_t schedule_at(std::int64_t step, double t_state) {
  vision_schedule_t schedule{};
  schedule.step = step;
  schedule.t_state = t_state;
  schedule.next_publication = schedule.next_capture = t_state + 1;
  return schedule;
}

truth_demand_t periodic_demand(double rate) {
  truth_demand_t demand{};
  demand.consumer = "viewer";
  demand.num_periodic = 1;
  demand.period = {1.0 / rate};
  demand.phase = {0.0};
  return demand;
}

TEST(PhysicsPacing, APacedStepWaitsUntilItIsDueAndThenRuns) {
  CoreOptions options;
  options.truth_on_demand = false;  // every step's state goes out
  Rig rig(options);
  PacedSteps paced(rig.loop, 0.25);
  paced.start(t0);
  Turn turn = paced.turn(t0);
  EXPECT_EQ(turn.kind, Kind::Wait);
  EXPECT_EQ(turn.until, t0 + wall(rig.dt()));
  EXPECT_EQ(rig.step(), 0);
  turn = paced.turn(t0 + wall(rig.dt()));
  EXPECT_EQ(turn.kind, Kind::Again) << "stepped: the next turn at once, no bus call";
  EXPECT_EQ(rig.step(), 1);
  EXPECT_EQ(rig.published(), (std::vector<std::int64_t>{1}));
  turn = paced.turn(t0 + wall(rig.dt()));
  EXPECT_EQ(turn.kind, Kind::Wait);
  EXPECT_EQ(turn.until, t0 + wall(2 * rig.dt()));
  // Twice real time, asked for 10 s later: the schedule starts again there,
  // from the current step, rather than racing to catch up.
  sim_control_t speed = control(sim_control_t::SET_SPEED);
  speed.speed_factor = 2;
  rig.core.on_control(speed, "");
  const auto t1 = t0 + 10s;
  turn = paced.turn(t1);
  EXPECT_EQ(turn.kind, Kind::Wait);
  EXPECT_EQ(turn.until, t1 + wall(rig.dt() / 2));
  EXPECT_EQ(rig.stats.schedule_restarts, 0);
  // Far behind its schedule (the machine could not keep up): it restarts, counted, and steps.
  turn = paced.turn(t1 + 1s);
  EXPECT_EQ(turn.kind, Kind::Again);
  EXPECT_EQ(rig.step(), 2);
  EXPECT_EQ(rig.stats.schedule_restarts, 1);
}

// States on demand: the steps before the next wanted state run when that one
// is due, one wakeup for four steps at a 60 Hz demand (docs/sync.md, "Steps nobody sees").
TEST(PhysicsPacing, PacedStepsNobodySeesRunWhenTheNextWantedStateIsDue) {
  Rig rig(CoreOptions{});
  rig.core.on_truth_demand(periodic_demand(60), t0);
  PacedSteps paced(rig.loop, 0.25);
  paced.start(t0);
  Turn turn = paced.turn(t0);
  EXPECT_EQ(turn.kind, Kind::Wait);
  EXPECT_EQ(turn.until, t0 + wall(4 * rig.dt()));
  for (int i = 0; i < 4; ++i) EXPECT_EQ(paced.turn(turn.until).kind, Kind::Again);
  EXPECT_EQ(paced.turn(turn.until).kind, Kind::Wait);
  EXPECT_EQ(rig.published(), (std::vector<std::int64_t>{4}));
}

TEST(PhysicsPacing, SyncStepsUpToTheHorizonThenWaitsCountedByWhatBoundsIt) {
  CoreOptions options;
  options.sync = true;
  Rig rig(options);
  SyncSteps sync(rig.loop);
  // No horizon yet: held. First what already waits on the bus, then a wait.
  EXPECT_EQ(sync.turn(t0).kind, Kind::Poll);
  Turn turn = sync.turn(t0);
  EXPECT_EQ(turn.kind, Kind::Wait);
  EXPECT_EQ(turn.until, t0 + 100ms);
  rig.loop.hold.settle(t0 + 40ms);
  const std::string before_any = horizon_bound_name(rig.core.horizon_bound());
  EXPECT_EQ(before_any, "the radio emulator (no SIM_SYNC_HORIZON yet)");
  EXPECT_EQ(rig.stats.sync_waits[before_any], 1);
  EXPECT_NEAR(rig.stats.sync_wait_seconds[before_any], 0.04, 1e-9);
  // A horizon three steps on: a look at the bus (its poll period), three steps, held again.
  rig.core.on_sync_horizon(horizon(3 * rig.dt(), "demo_blue"));
  const auto t1 = t0 + 50ms;
  EXPECT_EQ(sync.turn(t1).kind, Kind::Poll);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(sync.turn(t1).kind, Kind::Again);
  EXPECT_EQ(rig.step(), 3);
  EXPECT_EQ(sync.turn(t1).kind, Kind::Poll);
  EXPECT_EQ(sync.turn(t1).kind, Kind::Wait);
  rig.loop.hold.settle(t1 + 10ms);
  EXPECT_EQ(rig.stats.sync_waits["demo_blue"], 1);
  EXPECT_EQ(rig.stats.sync_waits[before_any], 1);
}

TEST(PhysicsPacing, AsFastAsPossibleLooksAtTheBusOnlyEveryPollPeriod) {
  CoreOptions options;
  options.speed = 0;
  Rig rig(options);
  VisionLead vision;
  AsFastAsPossible fast(rig.loop, vision, false);
  int polls = 0;
  auto now = t0;
  for (int turn = 0; turn < 100; ++turn, now += 10us) {
    const Kind kind = fast.turn(now).kind;
    ASSERT_TRUE(kind == Kind::Poll || kind == Kind::Again);
    polls += kind == Kind::Poll ? 1 : 0;
  }
  // 1 ms of turns: one look at the start and one per 200 us.
  EXPECT_EQ(polls, 5);
  EXPECT_EQ(rig.step(), 95);
}

// Turns as fast as possible at one wall time until one waits; returns the steps run.
std::int64_t steps_until_wait(AsFastAsPossible& fast, Rig& rig, Clock::time_point now, int limit) {
  const std::int64_t before = rig.step();
  for (int i = 0; i < limit; ++i) {
    if (fast.turn(now).kind == Kind::Wait) break;
  }
  return rig.step() - before;
}

// The first turn at a later wall time looks at the bus (its poll period
// passed); the next one is the policy's own.
Turn turn_after_poll(AsFastAsPossible& fast, Clock::time_point now) {
  EXPECT_EQ(fast.turn(now).kind, Kind::Poll);
  return fast.turn(now);
}

TEST(PhysicsPacing, AsFastAsPossibleRunsAtMostTheLeadAheadOfTheVision) {
  CoreOptions options;
  options.speed = 0;
  Rig rig(options);
  // One state a second wanted: the one physics waits at is not among them.
  rig.core.on_truth_demand(periodic_demand(1), t0);
  VisionLead vision;
  AsFastAsPossible fast(rig.loop, vision, false);
  EXPECT_EQ(steps_until_wait(fast, rig, t0, 100), 99) << "no vision heard: nothing to wait for";
  const std::size_t demanded = rig.published().size();
  // The vision has acknowledged the state at 0.5 s: physics goes on to 0.5 + the lead.
  vision.on_schedule(schedule_at(120, 0.5), t0);
  steps_until_wait(fast, rig, t0, 1000);
  EXPECT_NEAR(rig.core.world().time(), 0.5 + kVisionLead, rig.dt());
  // The state it waits at went out once, then the bus was looked at, then a
  // wait of at most 1 ms (the vision's schedules do not wake physics).
  EXPECT_EQ(rig.published().size(), demanded + 1);
  EXPECT_EQ(rig.stats.states_for_vision, 1);
  rig.loop.hold.settle(t0 + 1ms);
  EXPECT_EQ(rig.stats.vision_waits, 1);
  EXPECT_NEAR(rig.stats.vision_wait_seconds, 0.001, 1e-9);
  const auto t1 = t0 + 50ms;
  const Turn turn = turn_after_poll(fast, t1);
  ASSERT_EQ(turn.kind, Kind::Wait);
  EXPECT_EQ(turn.until, t1 + 1ms);
  rig.loop.hold.settle(t1 + 1ms);
  EXPECT_EQ(rig.stats.vision_waits, 2);
  EXPECT_EQ(rig.published().size(), demanded + 1) << "not again within 100 ms";
  turn_after_poll(fast, t0 + 100ms);
  EXPECT_EQ(rig.published().size(), demanded + 2)
      << "again after 100 ms (a vision may have missed it)";
  // A vision that listens but has seen no state yet (step -1) holds physics where it is.
  vision.on_schedule(schedule_at(-1, -1), t0 + 100ms);
  EXPECT_EQ(steps_until_wait(fast, rig, t0 + 100ms, 100), 0);
  vision.on_schedule(schedule_at(145, rig.core.world().time()), t0 + 100ms);
  EXPECT_GT(steps_until_wait(fast, rig, t0 + 100ms, 100), 0);
}

TEST(PhysicsPacing, VisionLeadStopsHoldingWhenTheVisionFallsSilent) {
  VisionLead vision;
  EXPECT_FALSE(vision.holds(1.0, 0.01, t0)) << "none heard";
  vision.on_schedule(schedule_at(0, 0), t0);
  EXPECT_TRUE(vision.holds(1.0, 0.01, t0 + kVisionSilence));
  EXPECT_FALSE(vision.holds(1.0, 0.01, t0 + kVisionSilence + 1ms));
  EXPECT_FALSE(vision.holds(1.0, 0.01, t0 + 2 * kVisionSilence));
  EXPECT_EQ(vision.silences(), 1) << "counted once per silence";
  vision.on_schedule(schedule_at(1, 0.5), t0 + 2 * kVisionSilence);
  EXPECT_TRUE(vision.holds(1.0, 0.01, t0 + 2 * kVisionSilence));
  EXPECT_FALSE(vision.holds(0.5, 0.01, t0 + 2 * kVisionSilence));
}

PacingOptions pacing_options() {
  PacingOptions options;
  options.poll_period = kPollPeriod;
  options.schedule_wakes = true;
  return options;
}

TEST(PhysicsPacing, SyncStartsOnceTheVisionListensAndTheRadioHasItsClients) {
  CoreOptions options;
  options.sync = true;
  options.duration = 0.05;  // 12 steps
  Rig rig(options);
  PhysicsPacing pacing(rig.core, rig.publisher, rig.stats, rig.stepping_clock, pacing_options());
  pacing.start(t0, true);
  EXPECT_EQ(pacing.turn(t0).kind, Kind::Wait);
  pacing.on_vision_schedule(schedule_at(-1, -1), t0);
  sync_horizon_t registering = horizon(1.0, "");
  registering.held_by = sync_horizon_t::HELD_BY_REGISTRATION;
  rig.core.on_sync_horizon(registering);
  pacing.on_sync_horizon(registering);
  EXPECT_EQ(pacing.turn(t0).kind, Kind::Wait) << "the radio waits for its clients";
  EXPECT_TRUE(rig.published().empty());
  // The hold is typed (held_by): a client may take any name, the one the
  // reason had as a string before included.
  rig.core.on_sync_horizon(horizon(1.0, "registration"));
  pacing.on_sync_horizon(horizon(1.0, "registration"));
  const auto t1 = t0 + 1s;
  EXPECT_EQ(pacing.turn(t1).kind, Kind::Again);
  EXPECT_EQ(rig.published(), (std::vector<std::int64_t>{0}));
  ASSERT_TRUE(pacing.gate().first_state_wall().has_value());
  EXPECT_TRUE(*pacing.gate().first_state_wall() == t1);
  // Up to the duration, then until the answers to the last frames are in.
  Turn turn;
  for (int i = 0; i < 100 && rig.step() < 12; ++i) turn = pacing.turn(t1);
  EXPECT_EQ(rig.step(), 12);
  turn = pacing.turn(t1);
  EXPECT_EQ(turn.kind, Kind::PollThenWait);
  EXPECT_EQ(turn.until, t1 + 100ms);
  rig.core.on_sync_horizon(horizon(1.0, "demo_blue", 0.06));
  EXPECT_EQ(pacing.turn(t1 + 10ms).kind, Kind::Finish);
}

TEST(PhysicsPacing, ASyncRunEndsAfterThreeSecondsWithoutTheLastAnswers) {
  CoreOptions options;
  options.sync = true;
  options.duration = 0.05;
  Rig rig(options);
  rig.core.on_sync_horizon(horizon(1.0, "demo_blue"));
  PhysicsPacing pacing(rig.core, rig.publisher, rig.stats, rig.stepping_clock, pacing_options());
  pacing.start(t0, false);
  for (int i = 0; i < 100 && rig.step() < 12; ++i) pacing.turn(t0);
  EXPECT_EQ(pacing.turn(t0).kind, Kind::PollThenWait);
  EXPECT_EQ(pacing.turn(t0 + 2900ms).until, t0 + 3s);
  EXPECT_EQ(pacing.turn(t0 + 3s).kind, Kind::Finish);
}

// Turns, with the wall clock moved on to where each wait ends, until `steps`
// steps ran or `limit` turns passed; returns the steps run.
std::int64_t run_steps(PhysicsPacing& pacing, Rig& rig, Clock::time_point& now, std::int64_t steps,
                       int limit) {
  const std::int64_t before = rig.step();
  for (int i = 0; i < limit && rig.step() - before < steps; ++i) {
    const Turn turn = pacing.turn(now);
    if (turn.kind == Kind::Wait) now = std::max(now, std::min(turn.until, now + 1s));
  }
  return rig.step() - before;
}

TEST(PhysicsPacing, OnlyAsFastAsPossibleOutsideSyncModeWaitsForTheVision) {
  struct Mode {
    double speed;
    bool sync;
    bool held;
    int turns;  // held: few enough that the vision does not fall silent (3 s)
  };
  for (const Mode mode :
       {Mode{1.0, false, false, 1000}, Mode{0.0, true, false, 1000}, Mode{0.0, false, true, 60}}) {
    CoreOptions options;
    options.speed = mode.speed;
    options.sync = mode.sync;
    Rig rig(options);
    rig.core.on_sync_horizon(horizon(10.0, "demo_blue"));
    PhysicsPacing pacing(rig.core, rig.publisher, rig.stats, rig.stepping_clock, pacing_options());
    pacing.start(t0, false);
    pacing.on_vision_schedule(schedule_at(0, 0), t0);
    auto now = t0;
    const std::int64_t steps = run_steps(pacing, rig, now, 100, mode.turns);
    if (mode.held) {
      EXPECT_NEAR(static_cast<double>(steps) * rig.dt(), kVisionLead, rig.dt());
    } else {
      EXPECT_EQ(steps, 100) << "speed " << mode.speed << (mode.sync ? " sync" : "");
    }
  }
}

TEST(PhysicsPacing, PausedWaitsAndResumedStepsOnAFreshSchedule) {
  CoreOptions options;
  options.paused = true;
  Rig rig(options);
  PhysicsPacing pacing(rig.core, rig.publisher, rig.stats, rig.stepping_clock, pacing_options());
  pacing.start(t0, false);
  EXPECT_EQ(pacing.turn(t0).kind, Kind::Wait);
  EXPECT_EQ(pacing.turn(t0 + 10s).kind, Kind::Wait);
  EXPECT_EQ(rig.step(), 0);
  rig.core.on_control(control(sim_control_t::RESUME), "");
  const auto t1 = t0 + 20s;
  const Turn turn = pacing.turn(t1);
  EXPECT_EQ(turn.kind, Kind::Wait) << "the schedule starts at the resume, not at the start";
  EXPECT_EQ(turn.until, t1 + wall(rig.dt()));
  EXPECT_EQ(pacing.turn(turn.until).kind, Kind::Again);
  EXPECT_EQ(rig.stats.schedule_restarts, 0);
}

}  // namespace
}  // namespace ubersim::physics::testing
