#include "ubersim/referee/autoref_rules.hpp"

#include <algorithm>
#include <cmath>

#include "ubersim/referee/situations.hpp"

namespace ubersim::referee {

int goal_side(const field_geometry_t& field, double x, double y, double z) {
  const double r = field.ball_radius;
  if (std::abs(x) <= field.field_length / 2 + r) return 0;
  if (std::abs(y) > field.goal_width / 2 || z > field.goal_height) return 0;
  return x > 0 ? 1 : -1;
}

BallOut ball_out(const field_geometry_t& field, double x, double y) {
  const double r = field.ball_radius;
  if (std::abs(x) > field.field_length / 2 + r) return BallOut::GoalLine;
  if (std::abs(y) > field.field_width / 2 + r) return BallOut::TouchLine;
  return BallOut::No;
}

double distance_to_out(const field_geometry_t& field, double x, double y) {
  const double r = field.ball_radius;
  return std::min(field.field_length / 2 + r - std::abs(x),
                  field.field_width / 2 + r - std::abs(y));
}

bool fully_in_defense_area(const field_geometry_t& field, int side, double x, double y,
                           double radius) {
  const double along = x * side;  // towards that goal line
  const double line = field.field_length / 2;
  return along >= line - field.penalty_area_depth + radius && along <= line &&
         std::abs(y) <= field.penalty_area_width / 2 - radius;
}

void free_kick_spot(const field_geometry_t& field, double& x, double& y) {
  const double limit_x = field.field_length / 2 - kFreeKickBoundaryDistance;
  const double limit_y = field.field_width / 2 - kFreeKickBoundaryDistance;
  x = std::clamp(x, -limit_x, limit_x);
  y = std::clamp(y, -limit_y, limit_y);
  // Out of the defence areas (and 0.2 m off them) along x, the shortest way out
  // for every spot the clamp leaves inside.
  const double inner_x =
      field.field_length / 2 - field.penalty_area_depth - kFreeKickBoundaryDistance;
  const double half_width = field.penalty_area_width / 2 + kFreeKickBoundaryDistance;
  if (std::abs(x) > inner_x && std::abs(y) < half_width) x = x > 0 ? inner_x : -inner_x;
}

bool heads_into_goal(const field_geometry_t& field, int side, double x, double y, double vx,
                     double vy) {
  const double line = side * field.field_length / 2;
  if (vx * side <= 1e-6) return false;  // not moving towards that goal line
  const double t = (line - x) / vx;
  if (t < 0) return false;
  return std::abs(y + vy * t) <= field.goal_width / 2;
}

}  // namespace ubersim::referee
