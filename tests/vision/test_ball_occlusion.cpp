// Ball occlusion by robots, checked against brute force: a point of the
// ball's silhouette is hidden when some height along its ray to the camera is
// inside the robot's footprint, tested at many heights.
#include <gtest/gtest.h>

#include <cmath>

#include "ubersim/vision/ball_occlusion.hpp"

using Eigen::Vector2d;
using Eigen::Vector3d;
using ubersim::vision::BallOcclusion;
using ubersim::vision::ray_hits_robot;
using ubersim::vision::RobotFootprint;

namespace {

constexpr double kBallRadius = 0.0215;

RobotFootprint robot_at(double x, double y, double heading) {
  RobotFootprint r;
  r.center = Vector2d(x, y);
  r.forward = Vector2d(std::cos(heading), std::sin(heading));
  r.radius = 0.09;
  r.height = 0.15;
  r.front_distance = 0.075;
  return r;
}

bool inside(const RobotFootprint& r, const Vector2d& p) {
  const Vector2d d = p - r.center;
  return d.norm() <= r.radius && d.dot(r.forward) <= r.front_distance;
}

// Brute force: walk up the ray in small height steps.
bool hidden_brute_force(const Vector3d& point, const Vector3d& camera, const RobotFootprint& r) {
  for (int i = 0; i <= 400; ++i) {
    const double z = point.z() + (r.height - point.z()) * i / 400.0;
    const double s = (z - point.z()) / (camera.z() - point.z());
    if (inside(r, (point + s * (camera - point)).head<2>())) return true;
  }
  return false;
}

struct Expected {
  double fraction;
  Vector2d center;
};

// Visible fraction and centre of the visible part on a fine grid.
Expected integrate(const Vector3d& camera, const Vector3d& ball, const RobotFootprint& r) {
  const int n = 120;
  int total = 0, visible = 0;
  Vector2d sum = Vector2d::Zero();
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const Vector2d offset(-1 + (2 * i + 1.0) / n, -1 + (2 * j + 1.0) / n);
      if (offset.norm() > 1) continue;
      ++total;
      const Vector3d p(ball.x() + kBallRadius * offset.x(), ball.y() + kBallRadius * offset.y(),
                       ball.z());
      if (!hidden_brute_force(p, camera, r)) {
        ++visible;
        sum += p.head<2>();
      }
    }
  }
  return {static_cast<double>(visible) / total,
          visible > 0 ? Vector2d(sum / visible) : Vector2d(ball.head<2>())};
}

}  // namespace

TEST(BallOcclusion, SegmentTestAgreesWithBruteForce) {
  const Vector3d camera(0.3, -0.2, 4.0);
  const RobotFootprint robot = robot_at(2.0, 0.5, 2.5);
  int disagreements = 0, hits = 0;
  for (int i = 0; i < 60; ++i) {
    for (int j = 0; j < 60; ++j) {
      const Vector3d p(1.75 + 0.5 * i / 59, 0.25 + 0.5 * j / 59, kBallRadius);
      const bool analytic = ray_hits_robot(p, camera, robot);
      hits += analytic;
      disagreements += analytic != hidden_brute_force(p, camera, robot);
    }
  }
  EXPECT_GT(hits, 300);
  // Brute force samples heights, so a ray grazing an edge may differ.
  EXPECT_LE(disagreements, 12);
}

TEST(BallOcclusion, FreeBallIsWhollyVisibleAtItsCentre) {
  const BallOcclusion occlusion;
  const Vector3d ball(1.0, 1.0, kBallRadius);
  const auto view = occlusion.view(Vector3d(0, 0, 4), ball, kBallRadius,
                                   {robot_at(-1, -1, 0), robot_at(1.3, 1.0, 0)});
  EXPECT_DOUBLE_EQ(view.visible_fraction, 1.0);
  EXPECT_EQ(view.visible_center, ball);
}

TEST(BallOcclusion, BallRightBehindARobotIsHidden) {
  const BallOcclusion occlusion;
  // Touching the robot's round back, on the far side from a camera over the
  // origin: the robot's top (0.15 m) hides the whole ball (0.043 m).
  const auto view =
      occlusion.view(Vector3d(0, 0, 4), Vector3d(2.0 + 0.09 + kBallRadius, 0, kBallRadius),
                     kBallRadius, {robot_at(2.0, 0, M_PI)});
  EXPECT_DOUBLE_EQ(view.visible_fraction, 0.0);
}

TEST(BallOcclusion, BallAtTheFlatFrontIsSeenFromAbove) {
  const BallOcclusion occlusion;
  // Touching the kicker face, camera right above the robot: the flat front
  // leaves the ball's near half visible, the round outline would not.
  const RobotFootprint robot = robot_at(0, 0, 0);
  const Vector3d ball(robot.front_distance + kBallRadius, 0, kBallRadius);
  const auto view = occlusion.view(Vector3d(0, 0, 4), ball, kBallRadius, {robot});
  const Expected expected = integrate(Vector3d(0, 0, 4), ball, robot);
  EXPECT_NEAR(view.visible_fraction, expected.fraction, 0.03);
  EXPECT_GT(view.visible_fraction, 0.3);
}

TEST(BallOcclusion, PartlyHiddenBallMatchesIntegration) {
  const BallOcclusion occlusion;
  const Vector3d camera(0, 0, 4);
  const RobotFootprint robot = robot_at(2.0, 0.0, M_PI / 3);
  for (const Vector3d& ball :
       {Vector3d(2.15, 0.0, kBallRadius), Vector3d(2.14, -0.08, kBallRadius),
        Vector3d(2.06, -0.1, kBallRadius), Vector3d(2.17, -0.03, kBallRadius)}) {
    const auto view = occlusion.view(camera, ball, kBallRadius, {robot});
    const Expected expected = integrate(camera, ball, robot);
    ASSERT_GT(expected.fraction, 0.02) << ball.transpose();
    ASSERT_LT(expected.fraction, 0.98) << ball.transpose();
    EXPECT_NEAR(view.visible_fraction, expected.fraction, 0.04) << ball.transpose();
    EXPECT_LT((view.visible_center.head<2>() - expected.center).norm(), 0.0015) << ball.transpose();
    EXPECT_DOUBLE_EQ(view.visible_center.z(), ball.z());
  }
}

TEST(BallOcclusion, BallAboveTheRobotsIsNeverHidden) {
  const BallOcclusion occlusion;
  const auto view =
      occlusion.view(Vector3d(0, 0, 4), Vector3d(2.0, 0, 0.3), kBallRadius, {robot_at(2.0, 0, 0)});
  EXPECT_DOUBLE_EQ(view.visible_fraction, 1.0);
}
