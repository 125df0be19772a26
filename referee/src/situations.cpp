#include "ubersim/referee/situations.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace ubersim::referee {
namespace {

// Index of `team`'s robot nearest to (x, y), or -1.
int nearest_robot(const PlacementScene& scene, Team team, double x, double y) {
  int best = -1;
  double best_distance = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < scene.robots.size(); ++i) {
    const auto& r = scene.robots[i];
    if (r.team != team) continue;
    const double d = std::hypot(r.x - x, r.y - y);
    if (d < best_distance) {
      best_distance = d;
      best = static_cast<int>(i);
    }
  }
  return best;
}

// Puts `robot` just behind the ball, facing (target_x, target_y), and fixes it.
void place_kicker(PlacedRobot& robot, const PlacementScene& scene, double target_x,
                  double target_y) {
  double ux = target_x - scene.ball_x;
  double uy = target_y - scene.ball_y;
  const double n = std::hypot(ux, uy);
  ux = n > 1e-9 ? ux / n : 1.0;
  uy = n > 1e-9 ? uy / n : 0.0;
  const double distance = robot.radius + scene.ball_radius + kKickerGap;
  robot.x = scene.ball_x - ux * distance;
  robot.y = scene.ball_y - uy * distance;
  robot.orientation = std::atan2(uy, ux);
  robot.ball_keep_out = 0;  // the kicker is the one robot allowed at the ball
  robot.fixed = true;
}

void keep_everyone_out(PlacementScene& scene, double distance_from_hull) {
  for (auto& r : scene.robots)
    r.ball_keep_out = std::max(r.ball_keep_out, distance_from_hull + r.radius);
}

// The `kicking` robot nearest to the ball goes behind it, facing the goal it
// attacks; `restart` names the situation when there is none.
void place_nearest_kicker(PlacementScene& scene, Team kicking, double attacked_goal_x,
                          const char* restart) {
  const int kicker = nearest_robot(scene, kicking, scene.ball_x, scene.ball_y);
  if (kicker < 0)
    throw std::runtime_error(std::string(restart) + ": no " + team_name(kicking) +
                             " robot on the field");
  place_kicker(scene.robots[static_cast<std::size_t>(kicker)], scene, attacked_goal_x, 0);
}

void plan_kickoff(PlacementScene& scene, Team kicking, const field_geometry_t& field,
                  FieldSides sides, double attacked_goal_x) {
  scene.ball_x = 0;
  scene.ball_y = 0;
  for (auto& r : scene.robots) {
    // Everyone in their own half, defenders outside the centre circle.
    const int own = sides.defends(r.team);
    if (own < 0)
      r.max_x = -r.radius;
    else
      r.min_x = r.radius;
    r.ball_keep_out =
        r.team == kicking ? kStopDistance + r.radius : field.center_circle_radius + r.radius;
    if (r.x * own < r.radius) r.x = own * std::max(std::abs(r.x), r.radius + kRobotGap);
  }
  place_nearest_kicker(scene, kicking, attacked_goal_x, "kick-off");
}

void plan_free_kick(PlacementScene& scene, const SituationRequest& request,
                    const field_geometry_t& field, double attacked_goal_x) {
  const double limit_x = field.field_length / 2 - kFreeKickBoundaryDistance;
  const double limit_y = field.field_width / 2 - kFreeKickBoundaryDistance;
  scene.ball_x = std::clamp(request.x, -limit_x, limit_x);
  scene.ball_y = std::clamp(request.y, -limit_y, limit_y);
  for (auto& r : scene.robots) {
    if (r.team != request.team) r.ball_keep_out = kStopDistance + r.radius;
  }
  place_nearest_kicker(scene, request.team, attacked_goal_x, "free kick");
}

void plan_penalty(PlacementScene& scene, Team kicking, const field_geometry_t& field,
                  FieldSides sides, double attacked_goal_x) {
  const Team other = kicking == Team::Yellow ? Team::Blue : Team::Yellow;
  const double attack = attacked_goal_x > 0 ? 1.0 : -1.0;
  scene.ball_x = penalty_mark_x(field, sides, kicking);
  scene.ball_y = 0;
  const int keeper = nearest_robot(scene, other, attacked_goal_x, 0);
  if (keeper >= 0) {
    auto& k = scene.robots[static_cast<std::size_t>(keeper)];
    k.x = attacked_goal_x - attack * k.radius;
    k.y = 0;
    k.orientation = attack > 0 ? M_PI : 0.0;
    k.fixed = true;
  }
  place_nearest_kicker(scene, kicking, attacked_goal_x, "penalty");
  for (auto& r : scene.robots) {
    if (r.fixed) continue;
    // Everyone else at least 1 m behind the ball, seen from the goal attacked.
    const double limit = scene.ball_x - attack * (kPenaltyBehindDistance + r.radius);
    if (attack > 0)
      r.max_x = limit;
    else
      r.min_x = limit;
    r.x = attack > 0 ? std::min(r.x, limit) : std::max(r.x, limit);
  }
}

}  // namespace

PlacementBounds bounds_of(const field_geometry_t& field) {
  // Robots may stand in the boundary area, not in or behind the walls; the
  // area behind the goal lines may be wider than along the touch lines.
  return {field.field_length / 2 + field.boundary_width_goal_line,
          field.field_width / 2 + field.boundary_width};
}

double penalty_mark_x(const field_geometry_t& field, FieldSides sides, Team kicking) {
  const Team defending = kicking == Team::Yellow ? Team::Blue : Team::Yellow;
  const int attacked_side = sides.defends(defending);
  return attacked_side * (field.field_length / 2 - field.penalty_mark_distance);
}

PlacementScene plan_situation(const SituationRequest& request, PlacementScene scene,
                              const field_geometry_t& field, FieldSides sides) {
  const double half_length = field.field_length / 2;
  const double half_width = field.field_width / 2;
  const Team kicking = request.team;
  const Team other = kicking == Team::Yellow ? Team::Blue : Team::Yellow;
  // The goal the kicking team attacks is the one the other team defends.
  const double attacked_goal_x = sides.defends(other) * half_length;

  for (auto& r : scene.robots) {
    r.fixed = false;
    r.ball_keep_out = 0;
    r.min_x = -1e9;
    r.max_x = 1e9;
  }

  switch (request.kind) {
    case Situation::Stop:
      keep_everyone_out(scene, kStopDistance);
      break;
    case Situation::BallPlacement:
      scene.ball_x = std::clamp(request.x, -half_length, half_length);
      scene.ball_y = std::clamp(request.y, -half_width, half_width);
      keep_everyone_out(scene, kStopDistance);
      break;
    case Situation::KickOff:
      plan_kickoff(scene, kicking, field, sides, attacked_goal_x);
      break;
    case Situation::FreeKick:
      plan_free_kick(scene, request, field, attacked_goal_x);
      break;
    case Situation::Penalty:
      plan_penalty(scene, kicking, field, sides, attacked_goal_x);
      break;
  }

  if (!separate(scene, bounds_of(field))) {
    throw std::runtime_error(
        "could not find legal places for every robot (too many robots for the field?)");
  }
  return scene;
}

}  // namespace ubersim::referee
