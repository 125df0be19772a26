// Worlds stepped at the same time on several threads (the Python VectorSim)
// share nothing: ODE's random generator is per thread
// (physics/model/src/ode_random.cpp) and each world has its own threading
// implementation (world.hpp), so their runs stay reproducible and ODE's
// process-wide job list is never raced on.
#include <gtest/gtest.h>
#include <ode/ode.h>

#include <cmath>
#include <thread>
#include <vector>

#include "ubersim/physics/world.hpp"

namespace {

TEST(WorldThreads, SameGeneratorAsLibode) {
  // libode 0.16: seed = 1664525 seed + 1013904223 (mod 2^32).
  dRandSetSeed(0);
  EXPECT_EQ(dRand(), 1013904223ul);
  EXPECT_EQ(dRand(), (1013904223ul * 1664525ul + 1013904223ul) & 0xffffffffUL);
}

TEST(WorldThreads, EachThreadHasItsOwnSeed) {
  dRandSetSeed(1);
  std::thread other([] { dRandSetSeed(2); });
  other.join();
  EXPECT_EQ(dRandGetSeed(), 1ul);
}

TEST(WorldThreads, LibodeDrawsFromTheCallingThreadsSeed) {
  // dRandInt lives in libode and calls dRand through its PLT: it must reach
  // the per-thread generator, not libode's process-wide one.
  dRandSetSeed(3);
  unsigned long after_other_thread = 0;
  std::thread other([&] {
    dRandSetSeed(7);
    for (int i = 0; i < 10; ++i) dRandInt(1000);
    after_other_thread = dRandGetSeed();
  });
  other.join();
  EXPECT_NE(after_other_thread, 7ul);
  EXPECT_EQ(dRandGetSeed(), 3ul);
}

// Every robot weaving on its own phase, commanded every 4 steps; the states
// of every step, flattened.
std::vector<double> run_world(std::uint64_t seed, int steps) {
  using namespace ubersim;
  physics::WorldSetup setup =
      physics::load_world_setup(UBERSIM_SOURCE_CONFIG_DIR, "division_b_6v6", "default");
  setup.seed = seed;
  physics::World world(setup);
  std::vector<double> trace;
  sim_state_t state;
  for (int s = 0; s < steps; ++s) {
    if (s % 4 == 0) {
      const double t = world.time();
      double phase = 0;
      for (const auto& robot : world.robots()) {
        robot_command_t c{};
        c.vx = 1.5 * std::cos(0.8 * t + phase);
        c.vy = 1.5 * std::sin(1.1 * t + 2 * phase);
        c.omega = 2.0 * std::sin(0.5 * t + phase);
        world.command(robot->team(), robot->id(), c);
        phase += 0.7;
      }
    }
    world.step();
    world.fill_state(state);
    for (const auto& r : state.robots) trace.insert(trace.end(), {r.x, r.y, r.orientation});
    trace.insert(trace.end(), state.ball.position, state.ball.position + 3);
  }
  return trace;
}

TEST(WorldThreads, WorldsSteppedTogetherOnThreadsMatchOneThread) {
  constexpr int kWorlds = 6;
  constexpr int kSteps = 960;  // 4 s
  std::vector<std::vector<double>> alone(kWorlds);
  for (int w = 0; w < kWorlds; ++w) alone[w] = run_world(w + 1, kSteps);
  std::vector<std::vector<double>> together(kWorlds);
  std::vector<std::thread> threads;
  for (int w = 0; w < kWorlds; ++w) {
    threads.emplace_back([&, w] {
      ubersim::physics::ensure_ode_initialised();
      together[w] = run_world(w + 1, kSteps);
    });
  }
  for (auto& thread : threads) thread.join();
  for (int w = 0; w < kWorlds; ++w) EXPECT_EQ(alone[w], together[w]) << "world " << w;
}

}  // namespace
