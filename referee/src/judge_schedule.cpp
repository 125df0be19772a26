// When the automatic referee must look again (AutoReferee::next_judge_time).
//
// Every rule decides on a condition of the ground truth: the ball wholly over
// a line, a robot within touching distance of the ball, the ball faster than a
// limit after a touch, the ball moved some distance, a clock ran out. Between
// two judged states none of these can become true sooner than the distances
// involved allow at the fastest the ball and the robots can move, so the
// referee names the first state at which one could, and the simulation (sync mode)
// runs up to it without a round trip per step. While the ball is in the air,
// touched, or about to be, that is the very next step.
#include <algorithm>
#include <cmath>
#include <ubersim/team_t.hpp>

#include "ubersim/referee/autoref.hpp"
#include "ubersim/referee/autoref_rules.hpp"

namespace ubersim::referee {
namespace {

// Robots: the fastest a robot can move within one judging period. SSL robots
// are limited to a few m/s; one robot pushed by another is not faster than
// the pusher. Used with the fastest robot seen now, times a margin.
constexpr double kRobotSpeedBound = 5.0;  // m/s
constexpr double kRobotSpeedMargin = 1.5;
// The largest hull radius of an SSL robot (rule: 0.09 m) with a margin: the
// ball can be pushed by a hull wider than the touch radius of the rules.
constexpr double kMaxHullRadius = 0.15;  // m
// The ball is not sped up without a contact; its rolling speed can still grow
// by its spin (|omega| r) and by numerical noise: a margin.
constexpr double kBallSpeedMargin = 1.05;
constexpr double kBallSpeedFloor = 0.05;  // m/s
// The ball is in the air (a chip, a bounce): it can fall faster, pass over
// robots and under the crossbar; judged every step.
constexpr double kAirborne = 0.005;  // m above resting height

double norm3(const double v[3]) {
  return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

}  // namespace

double AutoReferee::next_judge_time(const sim_state_t& state) const {
  const double dt = state.dt > 0 ? state.dt : 1.0 / 240;
  const double now = state.sim_time;
  double until = kMaxJudgePeriod;  // s from now: nothing can happen before then
  auto within = [&until](double seconds) { until = std::min(until, seconds); };

  // The clocks: each phase's deadline, the end of a half or of half time.
  switch (phase_) {
    case Phase::Start:
      within(0);
      break;
    case Phase::Stopped:
      within(phase_start_ + config_.stop_duration - now);
      break;
    case Phase::Prepared:
      within(phase_start_ + config_.prepare_duration - now);
      break;
    case Phase::AwaitKick:
      within(phase_start_ + config_.restart_timeout - now);
      break;
    case Phase::HalfTime:
      within(stage_end_ - now);
      break;
    case Phase::Running:
    case Phase::Over:
      break;
  }
  if (state_.stage == Stage::FirstHalf || state_.stage == Stage::SecondHalf) {
    within(stage_end_ - now);
  }
  if (placement_pending_) within(0);  // until the simulation shows the ball placed

  if (state.ball_present) {
    const auto& b = state.ball;
    const double ball_speed =
        kBallSpeedMargin *
            std::max(norm3(b.linear_velocity), norm3(b.angular_velocity) * field_.ball_radius) +
        kBallSpeedFloor;
    if (b.position[2] > field_.ball_radius + kAirborne) within(0);

    // Touches, in every phase (a touch during a stop names who is guilty of
    // the next out): a robot reaching the ball.
    double fastest = 0;
    for (const auto& r : state.robots) fastest = std::max(fastest, std::hypot(r.vx, r.vy));
    const double robot_speed = std::max(kRobotSpeedBound, kRobotSpeedMargin * fastest);
    const double contact =
        std::max(config_.robot_radius + config_.touch_margin, kMaxHullRadius) + field_.ball_radius;
    for (const auto& r : state.robots) {
      const double gap = std::hypot(r.x - b.position[0], r.y - b.position[1]) - contact;
      within(gap / (ball_speed + robot_speed));
    }

    const bool live = phase_ == Phase::AwaitKick || phase_ == Phase::Running;
    if (live) {
      within(distance_to_out(field_, b.position[0], b.position[1]) / ball_speed);
      // Speed limits after a touch not yet judged: only a contact speeds the
      // ball up past where its speed (and spin) could take it now.
      if (last_touch_ &&
          ((last_touch_->id != judged_speed_touch_ && ball_speed >= config_.max_ball_speed) ||
           (last_touch_->id != judged_shot_touch_ && ball_speed >= kShotSpeed))) {
        within(0);
      }
    }
    if (phase_ == Phase::AwaitKick) {
      const double moved =
          std::hypot(b.position[0] - kick_anchor_x_, b.position[1] - kick_anchor_y_);
      within((kKickedDistance - moved) / ball_speed);
    }
    if (phase_ == Phase::Running) {
      const double moved = std::hypot(b.position[0] - progress_x_, b.position[1] - progress_y_);
      within((config_.progress_distance - moved) / ball_speed);
      within(progress_time_ + config_.no_progress_time - now);
    }
  }
  if (phase_ == Phase::Running) {
    // Too many robots is repeated after no_progress_time while it lasts (a
    // robot added by hand is seen within kMaxJudgePeriod).
    for (Team team : kTeams) {
      int count = 0;
      for (const auto& r : state.robots) count += (r.team == team_t::BLUE) == (team == Team::Blue);
      if (count > config_.max_robots) {
        within(too_many_reported_[static_cast<int>(team)] + config_.no_progress_time - now);
      }
    }
  }
  // The first step at or after now + until (a hair earlier, so that a clock
  // that runs out exactly on a step is judged on that step): at least one.
  const double steps = std::max(1.0, std::ceil(until / dt - 1e-6));
  return now + steps * dt;
}

}  // namespace ubersim::referee
