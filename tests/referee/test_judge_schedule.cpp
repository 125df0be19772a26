// The referee's judging rate (AutoReferee::next_judge_time): judging only the
// states it names must decide exactly what judging every state decides. A
// small deterministic world (robots chasing and kicking the ball, the ball
// rolling, going out, into goals, carried to each restart's spot) runs at
// 240 Hz twice: once judged at every step, once only at the named steps. The
// event logs, commands and statistics must be the same, and the second must
// have judged far fewer states.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <ubersim/team_t.hpp>

#include "ubersim/config.hpp"
#include "ubersim/field_config.hpp"
#include "ubersim/referee/autoref.hpp"
#include "ubersim/referee/referee_message.hpp"

using namespace ubersim;
using namespace ubersim::referee;

namespace {

constexpr double kDt = 1.0 / 240;
constexpr double kBallRadius = 0.0215;

field_geometry_t division_b() {
  return load_field_config(UBERSIM_SOURCE_CONFIG_DIR, "division_b").to_message(kBallRadius);
}

// The world: each robot runs to the ball at its own speed, kicks it (at its
// own speed and aim: some shots too fast, some over the touch line, some into
// the goal) and rests a while; the ball rolls and slows. Everything a
// function of the step count, so two runs differ only by their referee.
class World {
 public:
  World() {
    state_.ball_present = true;
    state_.dt = kDt;
    for (int i = 0; i < 12; ++i) {
      robot_state_t r{};
      r.team = i < 6 ? team_t::YELLOW : team_t::BLUE;
      r.robot_id = i % 6;
      r.robot_type = "omni4_ssl";
      r.x = (i < 6 ? -1 : 1) * (0.8 + 0.6 * (i % 6));
      r.y = 2.0 - 0.8 * (i % 6);
      state_.robots.push_back(r);
      rest_until_.push_back(2.0 + 0.7 * i);  // not everyone at once
    }
    state_.num_robots = 12;
    ball(0, 0, 0, 0);
  }

  void ball(double x, double y, double vx, double vy) {
    auto& b = state_.ball;
    b.position[0] = x;
    b.position[1] = y;
    b.position[2] = kBallRadius;
    b.linear_velocity[0] = vx;
    b.linear_velocity[1] = vy;
  }

  void step(const RefereeState& referee) {
    auto& b = state_.ball;
    const bool play = referee.command != Command::Halt && referee.command != Command::Stop;
    for (std::size_t i = 0; i < state_.robots.size(); ++i) {
      auto& r = state_.robots[i];
      const double dx = b.position[0] - r.x, dy = b.position[1] - r.y;
      const double d = std::hypot(dx, dy);
      const double speed = 1.0 + 0.25 * static_cast<double>(i % 5);  // 1 .. 2 m/s
      const bool chasing = play && time_ >= rest_until_[i];
      // Chase; during a stop, back off to 0.6 m.
      double vx = 0, vy = 0;
      if (chasing && d > 0.1) {
        vx = speed * dx / d;
        vy = speed * dy / d;
      } else if (!play && d < 0.6 && d > 1e-9) {
        vx = -dx / d;
        vy = -dy / d;
      }
      r.vx = vx;
      r.vy = vy;
      r.x += vx * kDt;
      r.y += vy * kDt;
      if (chasing && d <= 0.11) {
        // Kick towards the other goal, at this robot's speed and aim.
        const double goal_x = r.team == team_t::YELLOW ? 4.5 : -4.5;
        const double aim_y = std::sin(1.7 * static_cast<double>(kicks_)) * 3.5;
        const double kx = goal_x - b.position[0], ky = aim_y - b.position[1];
        const double k = std::hypot(kx, ky);
        const double kick = 3.0 + 1.0 * static_cast<double>(kicks_ % 5);  // 3 .. 7 m/s
        b.linear_velocity[0] = kick * kx / k;
        b.linear_velocity[1] = kick * ky / k;
        rest_until_[i] = time_ + 1.5;
        ++kicks_;
      }
    }
    const double v = std::hypot(b.linear_velocity[0], b.linear_velocity[1]);
    if (v > 0) {
      const double slower = std::max(0.0, v - 0.4 * kDt) / v;  // rolling friction
      b.linear_velocity[0] *= slower;
      b.linear_velocity[1] *= slower;
    }
    b.position[0] += b.linear_velocity[0] * kDt;
    b.position[1] += b.linear_velocity[1] * kDt;
    ++step_;
    time_ = static_cast<double>(step_) * kDt;
    state_.step = step_;
    state_.sim_time = time_;
  }

  // Physics carries out a placement before the next step: the ball to the
  // referee's spot, at rest.
  void place(const RefereeState& referee) {
    if (referee.designated_position) {
      ball(referee.designated_position->first, referee.designated_position->second, 0, 0);
    } else {
      ball(state_.ball.position[0], state_.ball.position[1], 0, 0);
    }
  }

  const sim_state_t& state() const { return state_; }
  int kicks() const { return kicks_; }

 private:
  sim_state_t state_{};
  std::vector<double> rest_until_;
  std::int64_t step_ = 0;
  double time_ = 0;
  int kicks_ = 0;
};

struct Played {
  std::vector<std::string> log;  // event and command lines, as in the event log
  std::string result;
  long judged = 0;
  long steps = 0;
  int kicks = 0;
};

Played play(bool every_step) {
  GameConfig config = load_game_config(UBERSIM_SOURCE_CONFIG_DIR, "division_b");
  config.game_length = 40;
  AutoReferee referee(config, division_b());
  World world;
  Played run;
  double next = 0;
  while (!referee.state().game_over && run.steps < 240 * 120) {
    const auto& s = world.state();
    if (every_step || s.sim_time >= next - 1e-9) {
      ++run.judged;
      const auto d = referee.update(s);
      for (const auto& e : d.events) run.log.push_back(event_line(e));
      if (d.command_changed) run.log.push_back(command_line(referee.state(), s.sim_time));
      if (d.placement) world.place(referee.state());
      next = referee.next_judge_time(s);
      EXPECT_GE(next, s.sim_time + kDt - 1e-9);
    }
    world.step(referee.state());
    ++run.steps;
  }
  run.result = result_line(referee.state(), world.state().sim_time, 0);
  run.kicks = world.kicks();
  return run;
}

}  // namespace

TEST(JudgeSchedule, JudgingOnlyTheNamedStatesDecidesExactlyAsJudgingEveryState) {
  const Played all = play(true);
  const Played some = play(false);
  ASSERT_TRUE(all.result.find("\"game_over\": true") != std::string::npos) << all.result;
  // A game worth comparing: kicks, goals, outs and fouls happened.
  EXPECT_GT(all.kicks, 20);
  int goals = 0, outs = 0, fouls = 0;
  for (const auto& line : all.log) {
    goals += line.find("\"GOAL\"") != std::string::npos;
    outs += line.find("BALL_LEFT_FIELD") != std::string::npos;
    fouls += line.find("\"foul\": true") != std::string::npos;
  }
  EXPECT_GT(goals, 0);
  EXPECT_GT(outs, 0);
  EXPECT_GT(fouls, 0);
  ASSERT_EQ(all.log.size(), some.log.size());
  for (std::size_t i = 0; i < all.log.size(); ++i) EXPECT_EQ(all.log[i], some.log[i]) << i;
  EXPECT_EQ(all.result, some.result);
  EXPECT_EQ(all.steps, some.steps);
  std::printf("%d kicks, %d goals, %d outs, %d fouls; judged %ld of %ld states\n", all.kicks, goals,
              outs, fouls, some.judged, all.judged);
  // And it is worth it: most states were never looked at.
  EXPECT_LT(some.judged * 3, all.judged) << some.judged << " of " << all.judged;
}

TEST(JudgeSchedule, NamesTheNextStepWhileARobotIsOnTheBallAndAtMostATenthOfASecondAhead) {
  AutoReferee referee(load_game_config(UBERSIM_SOURCE_CONFIG_DIR, "division_b"), division_b());
  World world;
  sim_state_t s = world.state();
  referee.update(s);  // the start: STOP
  // Nobody near the ball, which rests: the stop's clock or the cap bounds it.
  EXPECT_NEAR(referee.next_judge_time(s), s.sim_time + AutoReferee::kMaxJudgePeriod, kDt);
  // A robot touching the ball: the very next step.
  s.robots[0].x = s.ball.position[0] - 0.1;
  s.robots[0].y = s.ball.position[1];
  EXPECT_NEAR(referee.next_judge_time(s), s.sim_time + kDt, 1e-12);
  // The ball in the air: the very next step.
  s.robots[0].x = -3;
  s.ball.position[2] = 0.1;
  EXPECT_NEAR(referee.next_judge_time(s), s.sim_time + kDt, 1e-12);
}
