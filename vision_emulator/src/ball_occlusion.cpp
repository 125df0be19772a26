#include "ubersim/vision/ball_occlusion.hpp"

#include <algorithm>
#include <cmath>

namespace ubersim::vision {

BallOcclusion::BallOcclusion(int rings, int points_per_ring) {
  samples_.reserve(static_cast<std::size_t>(rings) * static_cast<std::size_t>(points_per_ring));
  for (int ring = 0; ring < rings; ++ring) {
    // The radius that halves this ring's annulus of equal area.
    const double r = std::sqrt((ring + 0.5) / rings);
    const double offset = (ring % 2) * M_PI / points_per_ring;  // stagger neighbouring rings
    for (int k = 0; k < points_per_ring; ++k) {
      const double angle = offset + 2.0 * M_PI * k / points_per_ring;
      samples_.emplace_back(r * std::cos(angle), r * std::sin(angle));
    }
  }
}

bool ray_hits_robot(const Eigen::Vector3d& from, const Eigen::Vector3d& camera,
                    const RobotFootprint& robot) {
  const double z0 = std::max(from.z(), 0.0);
  if (z0 >= robot.height || camera.z() <= robot.height) return false;
  // The robot is a vertical prism, so the ray meets it if its horizontal trace
  // between the start and the robot's top height meets the footprint.
  const Eigen::Vector2d a = from.head<2>();
  const Eigen::Vector2d b = a + (camera.head<2>() - a) * ((robot.height - z0) / (camera.z() - z0));
  const Eigen::Vector2d e = b - a;
  const Eigen::Vector2d d0 = a - robot.center;

  // Disc: |d0 + t e|^2 <= R^2, t in [0, 1].
  double lo = 0, hi = 1;
  const double qa = e.squaredNorm();
  const double qb = 2.0 * d0.dot(e);
  const double qc = d0.squaredNorm() - robot.radius * robot.radius;
  if (qa < 1e-18) {
    if (qc > 0) return false;
  } else {
    const double discriminant = qb * qb - 4.0 * qa * qc;
    if (discriminant < 0) return false;
    const double root = std::sqrt(discriminant);
    lo = std::max(lo, (-qb - root) / (2.0 * qa));
    hi = std::min(hi, (-qb + root) / (2.0 * qa));
    if (lo > hi) return false;
  }
  // Flat front: (d0 + t e) . forward <= front_distance.
  const double g0 = d0.dot(robot.forward) - robot.front_distance;
  const double g1 = e.dot(robot.forward);
  if (std::abs(g1) < 1e-18) return g0 <= 0;
  const double t = -g0 / g1;
  if (g1 > 0) {
    hi = std::min(hi, t);
  } else {
    lo = std::max(lo, t);
  }
  return lo <= hi;
}

BallView BallOcclusion::view(const Eigen::Vector3d& camera, const Eigen::Vector3d& ball,
                             double ball_radius, const std::vector<RobotFootprint>& robots) const {
  BallView result;
  result.visible_center = ball;

  // Only robots whose shadow (as seen from the camera) can reach the ball.
  std::vector<const RobotFootprint*> near;
  const double to_camera = (camera.head<2>() - ball.head<2>()).norm() + ball_radius;
  for (const RobotFootprint& robot : robots) {
    if (ball.z() >= robot.height || camera.z() <= robot.height) continue;
    const double shadow = to_camera * (robot.height - std::max(ball.z(), 0.0)) /
                          (camera.z() - std::max(ball.z(), 0.0));
    const double reach = robot.radius + ball_radius + shadow;
    if ((robot.center - ball.head<2>()).squaredNorm() <= reach * reach) near.push_back(&robot);
  }
  if (near.empty()) return result;

  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  int visible = 0;
  for (const Eigen::Vector2d& sample : samples_) {
    const Eigen::Vector3d point(ball.x() + ball_radius * sample.x(),
                                ball.y() + ball_radius * sample.y(), ball.z());
    const bool hidden = std::any_of(near.begin(), near.end(), [&](const RobotFootprint* robot) {
      return ray_hits_robot(point, camera, *robot);
    });
    if (!hidden) {
      sum += point.head<2>();
      ++visible;
    }
  }
  if (visible == static_cast<int>(samples_.size())) return result;  // exact centre
  result.visible_fraction = static_cast<double>(visible) / static_cast<double>(samples_.size());
  if (visible > 0) result.visible_center.head<2>() = sum / visible;
  return result;
}

}  // namespace ubersim::vision
