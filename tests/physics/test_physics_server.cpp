// The server loop in-process on memq:// (no network): publication rate,
// commands over the bus, and the end of --duration.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>
#include <ubersim/referee_t.hpp>
#include <ubersim/sim_commands_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <ubersim/truth_demand_t.hpp>
#include <ubersim/vision_schedule_t.hpp>
#include <utility>

#include "physics_test_support.hpp"
#include "ubersim/message_bus.hpp"
#include "ubersim/physics/physics_core.hpp"
#include "ubersim/physics/physics_server.hpp"
#include "ubersim/shutdown.hpp"
#include "ubersim/vision_backpressure.hpp"

namespace ubersim::physics::testing {
namespace {

TEST(PhysicsServer, PublishesAtTheConfiguredRateAndStopsAtItsDuration) {
  WorldSetup setup = load_world_setup(kConfigDir, "field2002_5v5", "default");
  setup.physics.state_publish_rate = 60;  // every 4th step at 240 Hz
  MessageBus bus("memq://");
  ChannelNames channels;
  std::vector<sim_state_t> states;
  bus.subscribe<sim_state_t>(
      channels(Channel::SimState), [&](const sim_state_t& s) { states.push_back(s); }, 100000);
  ServerOptions options;
  options.speed = 0;
  options.duration = 1.0;
  PhysicsServer server(setup, bus, channels, options);
  EXPECT_EQ(server.run(nullptr), 0);
  bus.handle_pending();
  EXPECT_EQ(server.world().step_index(), 240);
  // One at start (step 0), then one per 1/60 s of sim time.
  ASSERT_EQ(states.size(), 61u);
  for (std::size_t i = 1; i < states.size(); ++i) {
    EXPECT_EQ(states[i].step, static_cast<int64_t>(4 * i));
    EXPECT_EQ(states[i].speed_factor, 0.0);
  }
  EXPECT_EQ(states.back().num_robots, 10);
}

TEST(PhysicsServer, CommandsOverTheBusMoveRobots) {
  WorldSetup setup = load_world_setup(kConfigDir, "division_b_6v6", "default");
  MessageBus bus("memq://");
  ChannelNames channels;
  ServerOptions options;
  options.speed = 0;
  options.duration = 1.0;
  PhysicsServer server(setup, bus, channels, options);
  sim_commands_t packet{};
  packet.team = 1;
  packet.t_apply = 0.25;
  packet.commands = {velocity_command(3, 1.0, 0, 0)};
  packet.num_commands = 1;
  bus.publish(channels(Channel::SimCommands), packet);
  const double x0 = server.world().robot(Team::Blue, 3)->planar_state().x;
  EXPECT_EQ(server.run(nullptr), 0);
  const Robot& robot = *server.world().robot(Team::Blue, 3);
  EXPECT_NEAR(robot.last_command_time(), 0.25, 1e-9);
  // Blue faces -x: 1 m/s forward is towards -x.
  EXPECT_LT(robot.planar_state().x, x0 - 0.3);
  EXPECT_EQ(server.stats().packets_received, 1);
}

// With --sync-referee physics steps up to the state the referee judges next;
// once the referee says the game is over, the state it judged last is the last
// one: two runs of a game end at the same state (docs/autoref.md).
TEST(PhysicsCore, HoldsAtTheStateTheRefereeEndedTheGameAt) {
  ServerOptions options;
  options.sync = true;
  options.sync_referee = true;
  PhysicsCore core(load_world_setup(kConfigDir, "division_b_6v6", "default"), options);
  EXPECT_FALSE(core.below_referee_horizon()) << "holds while no referee speaks";
  referee_t judged{};
  judged.sim_time = 0;
  judged.next_judge_time = 0.5;
  core.on_referee(judged);
  EXPECT_TRUE(core.below_referee_horizon());
  for (int i = 0; i < 24; ++i) core.step();
  judged.sim_time = core.world().time();
  judged.next_judge_time = judged.sim_time + 0.5;
  judged.game_over = true;
  core.on_referee(judged);
  EXPECT_FALSE(core.below_referee_horizon()) << "a step past the game's end";
}

vision_schedule_t schedule_at(std::int64_t step, double t_state) {
  vision_schedule_t schedule{};
  schedule.step = step;
  schedule.t_state = t_state;
  schedule.next_publication = schedule.next_capture = t_state + 1;
  return schedule;
}

// Steps the core until it waits for the vision (at most `limit` steps); returns the steps run.
int steps_until_vision_wait(PhysicsCore& core, PhysicsCore::Clock::time_point wall, int limit) {
  int steps = 0;
  while (steps < limit && !core.waits_for_vision(wall)) {
    core.step();
    ++steps;
  }
  return steps;
}

TEST(PhysicsCoreVision, AsFastAsPossibleRunsAtMostTheLeadAheadOfTheVision) {
  ServerOptions options;
  options.speed = 0;
  PhysicsCore core(load_world_setup(kConfigDir, "field2002_5v5", "default"), options);
  const auto wall = PhysicsCore::Clock::now();
  // One state a second wanted: the one physics waits at is not among them.
  truth_demand_t demand{};
  demand.consumer = "vision";
  demand.num_periodic = 1;
  demand.period = {1.0};
  demand.phase = {0.0};
  core.on_truth_demand(demand, wall);
  // No vision heard: nothing to wait for.
  EXPECT_EQ(steps_until_vision_wait(core, wall, 100), 100);
  // The vision has acknowledged the state at 0.5 s: physics goes on to 0.5 + the lead.
  core.on_vision_schedule(schedule_at(120, 0.5), wall);
  steps_until_vision_wait(core, wall, 1000);
  EXPECT_NEAR(core.world().time(), 0.5 + kVisionLead, core.world().dt());
  EXPECT_TRUE(core.waits_for_vision(wall));
  // The state it waits at goes out once (a demand may not have sent it), again only when asked.
  EXPECT_EQ(core.state_for_vision(false).states.size(), 1u);
  EXPECT_EQ(core.state_for_vision(false).states.size(), 0u);
  EXPECT_EQ(core.state_for_vision(true).states.size(), 1u);
  // A vision that listens but has seen no state yet (step -1) holds physics where it is.
  core.on_vision_schedule(schedule_at(-1, -1), wall);
  EXPECT_TRUE(core.waits_for_vision(wall));
  core.on_vision_schedule(schedule_at(145, core.world().time()), wall);
  EXPECT_FALSE(core.waits_for_vision(wall));
  // Silent for longer than kVisionSilence: physics stops waiting for it, counted once.
  steps_until_vision_wait(core, wall, 1000);
  EXPECT_TRUE(core.waits_for_vision(wall + kVisionSilence));
  EXPECT_FALSE(core.waits_for_vision(wall + kVisionSilence + std::chrono::milliseconds(1)));
  EXPECT_FALSE(core.waits_for_vision(wall + 2 * kVisionSilence));
  EXPECT_EQ(core.vision_silences(), 1);
  // It speaks again: physics waits for it again.
  core.on_vision_schedule(schedule_at(150, 0.6), wall + 2 * kVisionSilence);
  EXPECT_TRUE(core.waits_for_vision(wall + 2 * kVisionSilence));
}

TEST(PhysicsCoreVision, OnlyAsFastAsPossibleOutsideSyncModeWaitsForTheVision) {
  const auto wall = PhysicsCore::Clock::now();
  for (const auto& [speed, sync] : {std::pair{1.0, false}, std::pair{0.0, true}}) {
    ServerOptions options;
    options.speed = speed;
    options.sync = sync;
    PhysicsCore core(load_world_setup(kConfigDir, "field2002_5v5", "default"), options);
    core.on_vision_schedule(schedule_at(0, 0), wall);
    EXPECT_EQ(steps_until_vision_wait(core, wall, 100), 100) << "speed " << speed;
  }
}

TEST(PhysicsServer, WaitForVisionHoldsTheFirstStateUntilTheVisionListens) {
  WorldSetup setup = load_world_setup(kConfigDir, "field2002_5v5", "default");
  MessageBus bus("memq://");
  ChannelNames channels;
  std::vector<sim_state_t> states;
  bus.subscribe<sim_state_t>(
      channels(Channel::SimState), [&](const sim_state_t& s) { states.push_back(s); }, 100000);
  ServerOptions options;
  options.speed = 0;
  options.duration = 0.5;
  options.wait_for_vision = true;
  PhysicsServer server(setup, bus, channels, options);
  ShutdownSignal shutdown;
  std::thread stopper([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    shutdown.request();
  });
  EXPECT_EQ(server.run(&shutdown), 0);
  stopper.join();
  bus.handle_pending();
  // Nobody listened: no state, no step.
  EXPECT_EQ(server.world().step_index(), 0);
  EXPECT_TRUE(states.empty());
}

}  // namespace
}  // namespace ubersim::physics::testing
