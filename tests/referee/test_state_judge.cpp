// StateJudge with states anyone on the bus may send: one with a number that is
// not finite (or beyond 1e9), or a sim time that is not valid, is not judged,
// so none of it goes out in REFEREE or a placement (fuzzing.md, finding 16).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <ubersim/team_t.hpp>

#include "ubersim/field_config.hpp"
#include "ubersim/referee/state_judge.hpp"

using ubersim::referee::JudgeOptions;
using ubersim::referee::StateJudge;

namespace {

ubersim::sim_state_t state_at(double sim_time) {
  ubersim::sim_state_t state{};
  state.sim_time = sim_time;
  state.dt = 1.0 / 240;
  state.ball_present = true;
  ubersim::robot_state_t robot{};
  robot.team = ubersim::team_t::BLUE;
  robot.robot_id = 1;
  robot.x = 1.0;
  robot.robot_type = "omni4_ssl";
  ubersim::robot_state_t yellow = robot;
  yellow.team = ubersim::team_t::YELLOW;
  yellow.x = -1.0;
  state.robots = {robot, yellow};
  state.num_robots = 2;
  return state;
}

}  // namespace

TEST(StateJudge, AStateWithANumberNotFiniteOrATimeNotValidIsNotJudged) {
  const auto field =
      ubersim::load_field_config(UBERSIM_SOURCE_CONFIG_DIR, "division_b").to_message(0.0215);
  StateJudge judge(JudgeOptions{}, field, [](const std::string&) { return 0.09; });
  EXPECT_TRUE(judge.on_state(state_at(0.0)).judged);

  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto bad = state_at(60.0);  // past the first stop: the kick-off would be placed
  bad.robots[0].orientation = nan;
  auto out = judge.on_state(bad);
  EXPECT_FALSE(out.judged);
  EXPECT_FALSE(out.placement.has_value());
  EXPECT_FALSE(out.referee.has_value());
  bad = state_at(60.0);
  bad.ball.position[0] = 1e300;
  EXPECT_FALSE(judge.on_state(bad).judged);
  bad = state_at(nan);
  EXPECT_FALSE(judge.on_state(bad).judged);
  bad = state_at(2e9);
  EXPECT_FALSE(judge.on_state(bad).judged);
  EXPECT_EQ(judge.refused(), 4u);
  EXPECT_EQ(judge.judged(), 1u);

  // The same state with its numbers in order is judged, and what goes out is finite.
  out = judge.on_state(state_at(60.0));
  EXPECT_TRUE(out.judged);
  ASSERT_TRUE(out.placement.has_value());
  for (const auto& r : out.placement->robots) EXPECT_TRUE(std::isfinite(r.orientation));
}

// A field changed at run time (SIM_GEOMETRY after a SET_FIELD) is the field
// the next placement keeps the robots on.
TEST(StateJudge, PlacementsFollowAFieldChange) {
  auto field =
      ubersim::load_field_config(UBERSIM_SOURCE_CONFIG_DIR, "division_b").to_message(0.0215);
  StateJudge judge(JudgeOptions{}, field, [](const std::string&) { return 0.09; });
  EXPECT_TRUE(judge.on_state(state_at(0.0)).judged);
  field.field_length = 4.0;
  field.field_width = 3.0;
  field.boundary_width = 0.2;
  field.boundary_width_goal_line = 0.3;
  judge.set_field(field);
  auto state = state_at(60.0);  // the kick-off is placed
  state.robots[0].x = 4.0;      // inside division_b's walls, beyond the new ones
  const auto out = judge.on_state(state);
  ASSERT_TRUE(out.placement.has_value());
  bool blue_placed = false;
  for (const auto& r : out.placement->robots) {
    EXPECT_LE(std::abs(r.x), 2.0 + 0.3 - 0.09 + 1e-9);
    EXPECT_LE(std::abs(r.y), 1.5 + 0.2 - 0.09 + 1e-9);
    blue_placed = blue_placed || r.team == ubersim::team_t::BLUE;
  }
  EXPECT_TRUE(blue_placed);
}
