// The shell on its process host in-process on memq:// (no network):
// publication rate, commands over the bus, the end of --duration, the start
// gate; and the core's referee horizon and which states it publishes.
#include <gtest/gtest.h>

#include <chrono>
#include <ubersim/referee_t.hpp>
#include <ubersim/sim_commands_t.hpp>
#include <ubersim/sim_control_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <ubersim/truth_demand_t.hpp>
#include <vector>

#include "physics_test_support.hpp"
#include "ubersim/physics/physics_core.hpp"
#include "ubersim/physics/physics_shell.hpp"
#include "ubersim/process_host.hpp"
#include "ubersim/topics.hpp"

namespace ubersim::physics::testing {
namespace {

// Every SIM_STATE published on the host's bus, into `states`.
void record_states(ProcessHost& host, std::vector<sim_state_t>& states) {
  subscribe(
      host.bus(), host.channels(), topics::kSimState,
      [&states](const sim_state_t& s) { states.push_back(s); }, 100000);
}

ShellOptions as_fast_as_possible() {
  ShellOptions options;
  options.speed = 0;
  return options;
}

TEST(PhysicsShell, PublishesAtTheConfiguredRateAndStopsAtItsDuration) {
  WorldSetup setup = load_world_setup(kConfigDir, "field2002_5v5", "default");
  setup.physics.state_publish_rate = 60;  // every 4th step at 240 Hz
  ProcessHost host("memq://", ChannelNames(), "physics");
  std::vector<sim_state_t> states;
  record_states(host, states);
  ShellOptions options = as_fast_as_possible();
  options.duration = 1.0;
  PhysicsShell shell(setup, host, options);
  EXPECT_EQ(shell.run(), 0);
  host.bus().handle_pending();
  EXPECT_EQ(shell.world().step_index(), 240);
  // One at start (step 0), then one per 1/60 s of sim time.
  ASSERT_EQ(states.size(), 61u);
  for (std::size_t i = 1; i < states.size(); ++i) {
    EXPECT_EQ(states[i].step, static_cast<int64_t>(4 * i));
    EXPECT_EQ(states[i].speed_factor, 0.0);
  }
  EXPECT_EQ(states.back().num_robots, 10);
}

TEST(PhysicsShell, CommandsOverTheBusMoveRobots) {
  WorldSetup setup = load_world_setup(kConfigDir, "division_b_6v6", "default");
  ProcessHost host("memq://", ChannelNames(), "physics");
  ShellOptions options = as_fast_as_possible();
  options.duration = 1.0;
  PhysicsShell shell(setup, host, options);
  sim_commands_t packet{};
  packet.team = 1;
  packet.t_apply = 0.25;
  packet.commands = {velocity_command(3, 1.0, 0, 0)};
  packet.num_commands = 1;
  publish(host.bus(), host.channels(), topics::kSimCommands, packet);
  const double x0 = shell.world().robot(Team::Blue, 3)->planar_state().x;
  EXPECT_EQ(shell.run(), 0);
  const Robot& robot = *shell.world().robot(Team::Blue, 3);
  EXPECT_NEAR(robot.last_command_time(), 0.25, 1e-9);
  // Blue faces -x: 1 m/s forward is towards -x.
  EXPECT_LT(robot.planar_state().x, x0 - 0.3);
  EXPECT_EQ(shell.stats().packets_received, 1);
}

// With --sync-referee physics steps up to the state the referee judges next;
// once the referee says the game is over, the state it judged last is the last
// one: two runs of a game end at the same state (docs/autoref.md).
TEST(PhysicsCore, HoldsAtTheStateTheRefereeEndedTheGameAt) {
  CoreOptions options;
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

// Which steps' states go out: the union of what the consumers in the demand
// book want, physics' own (docs/sync.md, "Ground truth on demand") included.
constexpr double kStep = 1.0 / 240;

WorldSetup setup_at_state_rate(double rate) {
  WorldSetup setup = load_world_setup(kConfigDir, "field2002_5v5", "default");
  setup.physics.state_publish_rate = rate;
  return setup;
}

std::vector<std::int64_t> published_steps(PhysicsCore& core, int steps) {
  std::vector<std::int64_t> out;
  for (int i = 0; i < steps; ++i) {
    for (const sim_state_t& s : core.step().states) out.push_back(s.step);
  }
  return out;
}

truth_demand_t instants_demand(std::vector<double> instants) {
  truth_demand_t demand{};
  demand.consumer = "test";
  demand.num_instants = static_cast<std::int32_t>(instants.size());
  demand.instants = std::move(instants);
  return demand;
}

TEST(PhysicsCore, StatePublishRateThinsWhatGoesOutOnlyWhileNobodyAsks) {
  PhysicsCore core(setup_at_state_rate(60), CoreOptions{});
  EXPECT_EQ(published_steps(core, 8), (std::vector<std::int64_t>{4, 8}));
  core.on_truth_demand(instants_demand({10 * kStep}), PhysicsCore::Clock::now());
  EXPECT_EQ(published_steps(core, 8), (std::vector<std::int64_t>{10}));
}

TEST(PhysicsCore, TruthEveryStepWinsOverStatePublishRateAndDemands) {
  CoreOptions options;
  options.truth_on_demand = false;  // --truth-every-step
  PhysicsCore core(setup_at_state_rate(60), options);
  core.on_truth_demand(instants_demand({2 * kStep}), PhysicsCore::Clock::now());
  EXPECT_EQ(published_steps(core, 3), (std::vector<std::int64_t>{1, 2, 3}));
}

TEST(PhysicsCore, AStepRequestSeesEveryStateOfItsSteps) {
  PhysicsCore core(setup_at_state_rate(0), CoreOptions{});
  core.on_truth_demand(instants_demand({2 * kStep}), PhysicsCore::Clock::now());
  sim_control_t step{};
  step.action = sim_control_t::STEP;
  step.step_count = 3;
  const PhysicsCore::Output& out = core.on_control(step, "");
  ASSERT_EQ(out.states.size(), 3u);
  EXPECT_EQ(out.states.back().step, 3);
  EXPECT_TRUE(published_steps(core, 3).empty()) << "the instant was served by the request";
}

TEST(PhysicsCore, WithTheRefereeInSyncModeItsNextStateIsWantedBesideTheDemands) {
  CoreOptions options;
  options.sync = true;
  options.sync_referee = true;
  PhysicsCore core(setup_at_state_rate(60), options);
  EXPECT_EQ(published_steps(core, 2), (std::vector<std::int64_t>{1, 2}))
      << "every step while nobody asks, whatever the rate";
  core.on_truth_demand(instants_demand({4 * kStep}), PhysicsCore::Clock::now());
  referee_t judged{};
  judged.sim_time = 2 * kStep;
  judged.next_judge_time = 6 * kStep;
  core.on_referee(judged);
  EXPECT_EQ(published_steps(core, 4), (std::vector<std::int64_t>{4, 6}));
}

// A command beyond a robot type's limits is applied at the limit and counted where the user looks:
// the PING answer (`ubersim_referee ping`) and the summary at stop name how many, and which limit.
TEST(PhysicsCore, PingCountsTheCommandsAppliedAtARobotTypesLimit) {
  CoreOptions options;
  options.sync = true;
  PhysicsCore core(load_world_setup(kConfigDir, "division_b_6v6", "default"), options);
  robot_command_t kick = velocity_command(3, 0, 0, 0);
  kick.kick_speed = 10.0;  // omni4_ssl kicks at most 6.5 m/s
  sim_commands_t packet{};
  packet.team = 1;
  packet.t_apply = 0;
  packet.commands = {kick, velocity_command(2, 9.0, 0, 0)};  // at most 3.5 m/s
  packet.num_commands = 2;
  core.on_commands(packet);
  core.step();
  sim_control_t ping{};
  ping.action = sim_control_t::PING;
  const auto& out = core.on_control(ping, "none");
  ASSERT_TRUE(out.ack.has_value());
  EXPECT_NE(out.ack->message.find("commands: 2 applied, 2 (speed 1, kick speed 1) of them at a "
                                  "robot type's limit"),
            std::string::npos)
      << out.ack->message;
  EXPECT_EQ(command_summary(core.world().counters()).rfind("commands: 2 applied", 0), 0u);
}

TEST(PhysicsShell, WaitForVisionHoldsTheFirstStateUntilTheVisionListens) {
  WorldSetup setup = load_world_setup(kConfigDir, "field2002_5v5", "default");
  ProcessHost host("memq://", ChannelNames(), "physics");
  std::vector<sim_state_t> states;
  record_states(host, states);
  ShellOptions options = as_fast_as_possible();
  options.duration = 0.5;
  options.wait_for_vision = true;
  PhysicsShell shell(setup, host, options);
  host.every(std::chrono::milliseconds(300), [&](ProcessHost::Clock::time_point) { host.stop(0); });
  EXPECT_EQ(shell.run(), 0);
  host.bus().handle_pending();
  // Nobody listened: no state, no step.
  EXPECT_EQ(shell.world().step_index(), 0);
  EXPECT_TRUE(states.empty());
}

}  // namespace
}  // namespace ubersim::physics::testing
