// The link over a real TCP connection to a CI-mode stand-in for the game
// controller (standin_gc.hpp): the GC's clock is the sim time of the states
// the link judges, a goal its detectors see while the ball is in play reaches
// the GC as an autoref's POSSIBLE_GOAL, the GC's answer goes out as REFEREE in
// sim time naming the next state to stop at; and two runs are byte-identical.
#include <gtest/gtest.h>

#include <cmath>

#include "standin_gc.hpp"
#include "ubersim/field_config.hpp"
#include "ubersim/gc_link/ci_client.hpp"
#include "ubersim/gc_link/gc_link.hpp"
#include "ubersim/referee/autoref_config.hpp"

namespace {

using namespace ubersim;
using namespace ubersim::gc_link;

constexpr double kDt = 1.0 / 240;

// Ground truth of a small game: the ball waits at the centre for 2.5 s, then
// rolls into the goal at +x (yellow defends -x: a goal for yellow).
sim_state_t state_at(int step) {
  sim_state_t s{};
  s.sim_time = step * kDt;
  s.dt = kDt;
  s.ball_present = true;
  const double rolling = std::max(0.0, s.sim_time - 2.5);
  s.ball.position[0] = std::min(3.0 * rolling, 5.0);
  s.ball.position[2] = 0.0215;
  s.ball.linear_velocity[0] = rolling > 0 && s.ball.position[0] < 5.0 ? 3.0 : 0.0;
  return s;
}

struct GameRun {
  std::vector<std::vector<char>> referees;  // encoded referee_t, in order
  std::vector<double> tick_times;           // s, of the states the GC was ticked at
  std::vector<std::string> inputs;          // what the stand-in received, as sent
  int final_yellow = 0;
  int possible_goals = 0;
};

GameRun play(int steps) {
  standin::StandInGc gc;
  CiClient client("127.0.0.1:" + std::to_string(gc.port()), std::chrono::seconds(5));
  const auto field = load_field_config(UBERSIM_SOURCE_CONFIG_DIR, "division_b").to_message(0.0215);
  LinkOptions options;
  options.detectors = referee::load_game_config(UBERSIM_SOURCE_CONFIG_DIR, "division_b");
  GcLink link(options, field, [](const std::string&) { return 0.09; });
  GameRun run;
  for (int step = 0; step < steps; ++step) {
    const sim_state_t state = state_at(step);
    auto conversation = link.begin(state);
    if (conversation) {
      client.run(*conversation, std::chrono::seconds(5));
      run.tick_times.push_back(state.sim_time);
    }
    const LinkOutput out = link.finish(state, conversation ? &*conversation : nullptr);
    if (!out.referee) continue;
    EXPECT_DOUBLE_EQ(out.referee->sim_time, state.sim_time);
    EXPECT_GT(out.referee->next_judge_time, state.sim_time);
    std::vector<char> bytes(static_cast<std::size_t>(out.referee->getEncodedSize()));
    out.referee->encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    run.referees.push_back(bytes);
    run.final_yellow = out.referee->yellow_score;
  }
  run.inputs = gc.wire();
  for (const CiInput& input : gc.inputs()) {
    for (const Input& in : input.api_inputs()) {
      if (in.change().add_game_event_change().game_event().type() == GameEvent::POSSIBLE_GOAL) {
        ++run.possible_goals;
        EXPECT_EQ(in.change().add_game_event_change().game_event().possible_goal().by_team(),
                  YELLOW);
      }
    }
  }
  return run;
}

TEST(GcLinkPeer, TicksInSimTimeReportsTheGoalAndPublishesTheGcsAnswer) {
  const GameRun run = play(6 * 240);
  ASSERT_FALSE(run.tick_times.empty());
  // The GC's clock: each tick's timestamp is its state's sim time in ns.
  std::vector<std::int64_t> stamps;
  for (const std::string& bytes : run.inputs) {
    CiInput input;
    input.ParseFromString(bytes);
    if (input.has_timestamp()) stamps.push_back(input.timestamp());
  }
  ASSERT_EQ(stamps.size(), run.tick_times.size());
  for (std::size_t i = 0; i < stamps.size(); ++i) {
    EXPECT_EQ(stamps[i], std::llround(run.tick_times[i] * 1e9));
  }
  // Not every state: the GC is asked at its tick period or when there is news.
  EXPECT_LT(run.tick_times.size(), run.referees.size());
  EXPECT_EQ(run.possible_goals, 1);
  EXPECT_EQ(run.final_yellow, 1);
}

TEST(GcLinkPeer, TwoRunsAreByteIdentical) {
  const GameRun a = play(5 * 240);
  const GameRun b = play(5 * 240);
  EXPECT_EQ(a.inputs, b.inputs);
  EXPECT_EQ(a.referees, b.referees);
  EXPECT_GT(a.referees.size(), 100u);
}

}  // namespace
