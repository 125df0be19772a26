#include "ubersim/referee/placement.hpp"

#include <algorithm>
#include <cmath>

namespace ubersim::referee {
namespace {

constexpr double kTolerance = 1e-3;  // m
constexpr int kMaxIterations = 500;

// Direction to push a body that sits exactly on another: away from the field
// centre line on its own team's side, so the result is deterministic.
void fallback_direction(const PlacedRobot& robot, double& dx, double& dy) {
  dx = robot.team == Team::Yellow ? -1.0 : 1.0;
  dy = robot.id % 2 == 0 ? 0.3 : -0.3;
  const double n = std::hypot(dx, dy);
  dx /= n;
  dy /= n;
}

void clamp_to_bounds(PlacedRobot& robot, const PlacementBounds& bounds) {
  const double max_x = bounds.half_length - robot.radius;
  const double max_y = bounds.half_width - robot.radius;
  robot.x = std::clamp(robot.x, std::max(-max_x, robot.min_x), std::min(max_x, robot.max_x));
  robot.y = std::clamp(robot.y, -max_y, max_y);
}

bool inside(const PlacedRobot& robot, double x, double y, const PlacementBounds& bounds) {
  return std::abs(x) <= bounds.half_length - robot.radius &&
         std::abs(y) <= bounds.half_width - robot.radius && x >= robot.min_x && x <= robot.max_x;
}

// Moves the robot onto the keep-out circle around the ball: straight out if
// that point is allowed, else the nearest allowed point on the circle (tried
// in growing angles either side), so a ball near a wall or corner still works.
void push_out_of_ball_zone(PlacedRobot& robot, const PlacementScene& scene, double keep_out,
                           const PlacementBounds& bounds) {
  double dx = robot.x - scene.ball_x;
  double dy = robot.y - scene.ball_y;
  const double distance = std::hypot(dx, dy);
  if (distance < 1e-9) {
    fallback_direction(robot, dx, dy);
  } else {
    dx /= distance;
    dy /= distance;
  }
  const double radius = keep_out + kTolerance;
  const double base = std::atan2(dy, dx);
  constexpr int kSteps = 72;  // 2.5 degree steps, both ways round, up to half a turn each way
  for (int i = 0; i <= 2 * kSteps; ++i) {
    const double angle = base + (i % 2 == 0 ? 1 : -1) * ((i + 1) / 2) * (M_PI / kSteps);
    const double x = scene.ball_x + radius * std::cos(angle);
    const double y = scene.ball_y + radius * std::sin(angle);
    if (inside(robot, x, y, bounds)) {
      robot.x = x;
      robot.y = y;
      return;
    }
  }
  robot.x = scene.ball_x + dx * radius;  // nothing allowed: clamping will report it
  robot.y = scene.ball_y + dy * radius;
}

}  // namespace

bool is_legal(const PlacementScene& scene, const PlacementBounds& bounds) {
  const auto& robots = scene.robots;
  for (std::size_t i = 0; i < robots.size(); ++i) {
    const auto& a = robots[i];
    if (!a.fixed && (a.x < a.min_x - kTolerance || a.x > a.max_x + kTolerance)) return false;
    if (std::abs(a.x) > bounds.half_length - a.radius + kTolerance ||
        std::abs(a.y) > bounds.half_width - a.radius + kTolerance) {
      return false;
    }
    const double keep_out = std::max(a.ball_keep_out, a.radius + scene.ball_radius);
    if (std::hypot(a.x - scene.ball_x, a.y - scene.ball_y) < keep_out - kTolerance) return false;
    for (std::size_t j = i + 1; j < robots.size(); ++j) {
      const auto& b = robots[j];
      if (std::hypot(a.x - b.x, a.y - b.y) < a.radius + b.radius + kRobotGap - kTolerance) {
        return false;
      }
    }
  }
  return true;
}

bool separate(PlacementScene& scene, const PlacementBounds& bounds) {
  auto& robots = scene.robots;
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    bool moved = false;
    for (auto& robot : robots) {
      if (robot.fixed) continue;
      // Keep out of the ball's zone: push radially outwards.
      const double keep_out = std::max(robot.ball_keep_out, robot.radius + scene.ball_radius);
      if (std::hypot(robot.x - scene.ball_x, robot.y - scene.ball_y) < keep_out) {
        push_out_of_ball_zone(robot, scene, keep_out, bounds);
        moved = true;
      }
      const double before_x = robot.x, before_y = robot.y;
      clamp_to_bounds(robot, bounds);
      moved = moved || before_x != robot.x || before_y != robot.y;
    }
    for (std::size_t i = 0; i < robots.size(); ++i) {
      for (std::size_t j = i + 1; j < robots.size(); ++j) {
        auto& a = robots[i];
        auto& b = robots[j];
        if (a.fixed && b.fixed) continue;
        const double needed = a.radius + b.radius + kRobotGap;
        double dx = b.x - a.x;
        double dy = b.y - a.y;
        const double distance = std::hypot(dx, dy);
        if (distance >= needed) continue;
        if (distance < 1e-9) {
          fallback_direction(b, dx, dy);
        } else {
          dx /= distance;
          dy /= distance;
        }
        const double overlap = needed - distance + kTolerance;
        const double share_a = a.fixed ? 0.0 : (b.fixed ? 1.0 : 0.5);
        const double share_b = 1.0 - share_a;
        a.x -= dx * overlap * share_a;
        a.y -= dy * overlap * share_a;
        b.x += dx * overlap * share_b;
        b.y += dy * overlap * share_b;
        moved = true;
      }
    }
    if (!moved) break;
  }
  return is_legal(scene, bounds);
}

}  // namespace ubersim::referee
