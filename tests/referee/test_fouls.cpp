// The foul detectors (fouls.hpp), one situation each, without the referee's
// state machine: the state is built by hand and the returned event checked,
// and the nearest situation that is no foul returns nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <ubersim/team_t.hpp>

#include "ubersim/field_config.hpp"
#include "ubersim/referee/autoref_config.hpp"
#include "ubersim/referee/fouls.hpp"

using namespace ubersim;
using namespace ubersim::referee;

namespace {

constexpr double kBallRadius = 0.0215;  // m

field_geometry_t division_b() {
  return load_field_config(UBERSIM_SOURCE_CONFIG_DIR, "division_b").to_message(kBallRadius);
}

GameConfig shipped_config() {
  return load_game_config(UBERSIM_SOURCE_CONFIG_DIR, "division_b");
}

robot_state_t robot(Team team, int id, double x, double y) {
  robot_state_t r{};
  r.team = team == Team::Blue ? team_t::BLUE : team_t::YELLOW;
  r.robot_id = id;
  r.robot_type = "omni4_ssl";
  r.x = x;
  r.y = y;
  return r;
}

sim_state_t with_ball(double x, double y, double vx = 0, double vy = 0, double vz = 0,
                      double z = kBallRadius) {
  sim_state_t state{};
  state.ball_present = true;
  state.ball.position[0] = x;
  state.ball.position[1] = y;
  state.ball.position[2] = z;
  state.ball.linear_velocity[0] = vx;
  state.ball.linear_velocity[1] = vy;
  state.ball.linear_velocity[2] = vz;
  return state;
}

void add(sim_state_t& state, const robot_state_t& r) {
  state.robots.push_back(r);
  state.num_robots = static_cast<int32_t>(state.robots.size());
}

}  // namespace

TEST(FoulDoubleTouch, TheKickerTouchingAgainIsAFoulPlacedWhereItKicked) {
  const BallTouch kicker{Team::Blue, 3, 1.0, -0.5, 7};
  const BallTouch again{Team::Blue, 3, 1.4, -0.4, 8};
  const auto foul = double_touch(kicker, again);
  ASSERT_TRUE(foul.has_value());
  EXPECT_EQ(foul->type, EventType::AttackerDoubleTouchedBall);
  EXPECT_EQ(foul->team, Team::Blue);
  EXPECT_EQ(foul->robot, 3);
  EXPECT_TRUE(foul->foul);
  EXPECT_TRUE(foul->has_location);
  EXPECT_EQ(foul->x, 1.0);
  EXPECT_EQ(foul->y, -0.5);
  EXPECT_EQ(foul->description, "blue 3 touched the ball twice after its restart: free kick yellow");
}

TEST(FoulDoubleTouch, TheKickItselfATeamMateOrTheOtherTeamsSameIdIsNoFoul) {
  const BallTouch kicker{Team::Blue, 3, 1.0, -0.5, 7};
  EXPECT_FALSE(double_touch(kicker, kicker).has_value());
  EXPECT_FALSE(double_touch(kicker, BallTouch{Team::Blue, 2, 1.4, -0.4, 8}).has_value());
  EXPECT_FALSE(double_touch(kicker, BallTouch{Team::Yellow, 3, 1.4, -0.4, 8}).has_value());
}

TEST(FoulBallTooFast, FasterThanTheLimitInThreeDimensionsIsAFoulOfTheLastToucher) {
  const BallTouch touch{Team::Yellow, 5, 0.0, 0.0, 2};
  // 6 m/s along the ground and 3 m/s up: 6.7 m/s, over 6.5.
  const auto foul = ball_too_fast(with_ball(0.5, 0.25, 6.0, 0.0, 3.0), touch, 6.5);
  ASSERT_TRUE(foul.has_value());
  EXPECT_EQ(foul->type, EventType::BotKickedBallTooFast);
  EXPECT_EQ(foul->team, Team::Yellow);
  EXPECT_EQ(foul->robot, 5);
  EXPECT_TRUE(foul->foul);
  EXPECT_EQ(foul->x, 0.5);  // where the ball is
  EXPECT_EQ(foul->y, 0.25);
  EXPECT_NEAR(foul->value, std::hypot(6.0, 3.0), 1e-12);
  EXPECT_EQ(foul->description, "yellow 5 kicked the ball at 6.71 m/s (limit 6.5)");
}

TEST(FoulBallTooFast, AtTheLimitIsNoFoul) {
  const BallTouch touch{Team::Yellow, 5, 0.0, 0.0, 2};
  EXPECT_FALSE(ball_too_fast(with_ball(0, 0, 6.5, 0, 0), touch, 6.5).has_value());
  EXPECT_FALSE(ball_too_fast(with_ball(0, 0, 0, -6.4, 0), touch, 6.5).has_value());
}

// Blue defends +x: its defence area is x in [3.5, 4.5], |y| <= 1 on Division B.
TEST(FoulDefenderInDefenseArea, ADefenderTouchingTheBallWhollyInsideIsAFoulPlacedAtTheRobot) {
  sim_state_t state = with_ball(3.8 - 0.12, 0.6);
  add(state, robot(Team::Yellow, 4, 3.8, -0.6));  // an attacker in the area is not judged here
  add(state, robot(Team::Blue, 4, 3.8, 0.6));
  const auto foul = defender_in_defense_area(state, division_b(), FieldSides{}, shipped_config());
  ASSERT_TRUE(foul.has_value());
  EXPECT_EQ(foul->type, EventType::DefenderInDefenseArea);
  EXPECT_EQ(foul->team, Team::Blue);
  EXPECT_EQ(foul->robot, 4);
  EXPECT_TRUE(foul->foul);
  EXPECT_EQ(foul->x, 3.8);
  EXPECT_EQ(foul->y, 0.6);
  EXPECT_EQ(foul->description,
            "blue 4 touched the ball inside its own defence area: penalty yellow");
}

TEST(FoulDefenderInDefenseArea, TheKeeperPartlyInsideOutOfReachOrUnderABallInTheAirIsNoFoul) {
  const auto field = division_b();
  const auto config = shipped_config();  // keepers: robot 0
  auto judge = [&](const robot_state_t& r, const sim_state_t& ball) {
    sim_state_t state = ball;
    add(state, r);
    return defender_in_defense_area(state, field, FieldSides{}, config).has_value();
  };
  EXPECT_TRUE(judge(robot(Team::Blue, 4, 3.8, 0.6), with_ball(3.68, 0.6)));    // the foul itself
  EXPECT_FALSE(judge(robot(Team::Blue, 0, 3.8, 0.6), with_ball(3.68, 0.6)));   // keeper
  EXPECT_FALSE(judge(robot(Team::Blue, 4, 3.55, 0.6), with_ball(3.43, 0.6)));  // partly out
  EXPECT_FALSE(judge(robot(Team::Blue, 4, 3.8, 0.6), with_ball(3.5, 0.6)));    // out of reach
  EXPECT_FALSE(judge(robot(Team::Blue, 4, 3.8, 0.6),
                     with_ball(3.68, 0.6, 0, 0, 0, 0.2)));  // ball over the robot
  // The same spot on the other side is yellow's attacking area, not its own.
  EXPECT_FALSE(judge(robot(Team::Yellow, 4, 3.8, 0.6), with_ball(3.68, 0.6)));
}

TEST(FoulTooManyRobots, MoreThanTheLimitIsAFoulPlacedAtTheBall) {
  sim_state_t state = with_ball(-1.0, 2.0);
  for (int id = 0; id < 7; ++id) add(state, robot(Team::Yellow, id, -1.0 - 0.3 * id, 0));
  for (int id = 0; id < 6; ++id) add(state, robot(Team::Blue, id, 1.0 + 0.3 * id, 0));
  const auto foul = too_many_robots(state, Team::Yellow, 6);
  ASSERT_TRUE(foul.has_value());
  EXPECT_EQ(foul->type, EventType::TooManyRobots);
  EXPECT_EQ(foul->team, Team::Yellow);
  EXPECT_EQ(foul->robot, -1);
  EXPECT_TRUE(foul->foul);
  EXPECT_EQ(foul->x, -1.0);
  EXPECT_EQ(foul->y, 2.0);
  EXPECT_EQ(foul->value, 7);
  EXPECT_EQ(foul->description, "yellow has 7 robots on the field (6 allowed): free kick blue");
  EXPECT_FALSE(too_many_robots(state, Team::Blue, 6).has_value());  // blue has its 6
  EXPECT_FALSE(too_many_robots(state, Team::Yellow, 7).has_value());
}

TEST(GameEventMaking, FoulsCountAsFoulsAndEveryEventHasAPlace) {
  const auto goal = make_event(EventType::Goal, {Team::Blue, 2}, 4.6, 0.1, "goal for blue");
  EXPECT_FALSE(goal.foul);
  EXPECT_TRUE(goal.has_location);
  EXPECT_EQ(goal.team, Team::Blue);
  EXPECT_EQ(goal.robot, 2);
  EXPECT_EQ(goal.value, 0);
  const auto stalled = make_event(EventType::NoProgressInGame, {}, 1, 2, "no progress", 10.5);
  EXPECT_FALSE(stalled.team.has_value());
  EXPECT_EQ(stalled.robot, -1);
  EXPECT_EQ(stalled.value, 10.5);
  for (EventType foul : {EventType::AttackerDoubleTouchedBall, EventType::BotKickedBallTooFast,
                         EventType::DefenderInDefenseArea, EventType::TooManyRobots}) {
    EXPECT_TRUE(is_foul(foul)) << event_name(foul);
  }
  for (EventType event : {EventType::NoProgressInGame, EventType::BallLeftFieldTouchLine,
                          EventType::BallLeftFieldGoalLine, EventType::Goal}) {
    EXPECT_FALSE(is_foul(event)) << event_name(event);
  }
}
