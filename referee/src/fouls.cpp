#include "ubersim/referee/fouls.hpp"

#include <cmath>
#include <string>
#include <ubersim/team_t.hpp>

#include "ubersim/referee/autoref_rules.hpp"

namespace ubersim::referee {

std::optional<GameEvent> double_touch(const BallTouch& kicker, const BallTouch& last_touch) {
  if (last_touch.id == kicker.id) return std::nullopt;  // still the kick itself
  if (last_touch.team != kicker.team || last_touch.robot != kicker.robot) return std::nullopt;
  return make_event(
      EventType::AttackerDoubleTouchedBall, {kicker.team, kicker.robot}, kicker.x, kicker.y,
      robot_name(kicker.team, kicker.robot) +
          " touched the ball twice after its restart: free kick " + team_name(other(kicker.team)));
}

std::optional<GameEvent> ball_too_fast(const sim_state_t& state, const BallTouch& last_touch,
                                       double max_ball_speed) {
  const auto& v = state.ball.linear_velocity;
  const double speed = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (!(speed > max_ball_speed)) return std::nullopt;
  return make_event(EventType::BotKickedBallTooFast, {last_touch.team, last_touch.robot},
                    state.ball.position[0], state.ball.position[1],
                    robot_name(last_touch.team, last_touch.robot) + " kicked the ball at " +
                        short_number(speed) + " m/s (limit " + short_number(max_ball_speed) + ")",
                    speed);
}

std::optional<GameEvent> defender_in_defense_area(const sim_state_t& state,
                                                  const field_geometry_t& field,
                                                  const FieldSides& sides,
                                                  const GameConfig& config) {
  const double bx = state.ball.position[0], by = state.ball.position[1];
  if (state.ball.position[2] >= kRobotHeight) return std::nullopt;  // over every robot
  const double reach = config.robot_radius + field.ball_radius + config.touch_margin;
  for (const auto& r : state.robots) {
    const Team team = team_of(r);
    if (r.robot_id == config.keeper(team)) continue;
    if (!fully_in_defense_area(field, sides.defends(team), r.x, r.y, config.robot_radius)) {
      continue;
    }
    if (std::hypot(r.x - bx, r.y - by) > reach) continue;
    return make_event(EventType::DefenderInDefenseArea, {team, r.robot_id}, r.x, r.y,
                      robot_name(team, r.robot_id) +
                          " touched the ball inside its own defence area: penalty " +
                          team_name(other(team)));
  }
  return std::nullopt;
}

std::optional<GameEvent> too_many_robots(const sim_state_t& state, Team team, int max_robots) {
  int count = 0;
  for (const auto& r : state.robots) count += team_of(r) == team ? 1 : 0;
  if (count <= max_robots) return std::nullopt;
  return make_event(
      EventType::TooManyRobots, {team, -1}, state.ball.position[0], state.ball.position[1],
      std::string(team_name(team)) + " has " + std::to_string(count) + " robots on the field (" +
          std::to_string(max_robots) + " allowed): free kick " + team_name(other(team)),
      count);
}

}  // namespace ubersim::referee
