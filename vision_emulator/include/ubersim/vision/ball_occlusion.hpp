#pragma once
// How much of the ball one camera sees past the robots. A robot is an upright
// prism: a disc of its radius cut flat at its front (kicker face), from the
// ground up to its height. The ball's silhouette is taken as a disc of its
// radius in the horizontal plane through its centre; the disc is sampled at
// points of equal area, and a sample is hidden when the ray from it up to the
// camera passes through a robot. The camera is far above the ball, so the
// disc stands for the silhouette to a fraction of a millimetre.
#include <Eigen/Core>
#include <vector>

namespace ubersim::vision {

struct RobotFootprint {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();    // m
  Eigen::Vector2d forward = Eigen::Vector2d::UnitX();  // unit heading
  double radius = 0;                                   // m
  double height = 0;                                   // m
  double front_distance = 0;                           // m, centre to the flat front
};

struct BallView {
  double visible_fraction = 1;  // 0..1 of the silhouette's area
  // Centre of the visible part (m), in the plane of the ball's centre; the
  // ball's centre itself when nothing hides it.
  Eigen::Vector3d visible_center = Eigen::Vector3d::Zero();
};

class BallOcclusion {
 public:
  // rings x points_per_ring samples; each ring holds an equal share of the area
  // and its points are evenly spaced, so the samples' centroid is the centre.
  explicit BallOcclusion(int rings = 8, int points_per_ring = 16);

  BallView view(const Eigen::Vector3d& camera, const Eigen::Vector3d& ball, double ball_radius,
                const std::vector<RobotFootprint>& robots) const;

  std::size_t sample_count() const { return samples_.size(); }

 private:
  std::vector<Eigen::Vector2d> samples_;  // on the unit disc
};

// Whether the ray from `ground` (at height z) up to `camera` passes through the robot.
bool ray_hits_robot(const Eigen::Vector3d& from, const Eigen::Vector3d& camera,
                    const RobotFootprint& robot);

}  // namespace ubersim::vision
