#pragma once
// Wheel kinematics of any wheeled robot (the paper's w = T^-1 v).
//
// Wheel i sits at p_i (robot frame) and drives along the unit vector d_i with
// radius r. Rolling without slip ties its speed to the robot's velocity
// v = (vx, vy, omega):  w_i = (d_i . (vx, vy) + omega (p_i x d_i)) / r.
// Stacked, that is w = T^-1 v, an n x 3 matrix for n wheels. Its
// pseudo-inverse T (3 x n) recovers the robot's velocity from wheel speeds in
// the least-squares sense; for a differential drive (rank 2) it gives the
// velocity with no sideways part, which is all two fixed wheels can do.
#include <Eigen/Dense>

#include "ubersim/robot_config.hpp"

namespace ubersim::physics {

class WheelKinematics {
 public:
  explicit WheelKinematics(const RobotTypeConfig& robot);

  std::size_t wheel_count() const { return static_cast<std::size_t>(inverse_.rows()); }
  // Robot-frame velocity (m/s, m/s, rad/s) -> wheel speeds (rad/s).
  Eigen::VectorXd wheel_speeds(const Eigen::Vector3d& velocity) const {
    return inverse_ * velocity;
  }
  // Wheel speeds (rad/s) -> robot-frame velocity, least squares.
  Eigen::Vector3d velocity(const Eigen::VectorXd& wheel_speeds) const {
    return forward_ * wheel_speeds;
  }
  const Eigen::MatrixXd& inverse() const { return inverse_; }  // T^-1, n x 3
  const Eigen::MatrixXd& forward() const { return forward_; }  // T, 3 x n

 private:
  Eigen::MatrixXd inverse_;
  Eigen::MatrixXd forward_;
};

// Wheel geometry in the robot frame (m): contact point and driving direction.
struct WheelGeometry {
  double x = 0, y = 0;    // contact point relative to the robot centre
  double dx = 0, dy = 0;  // unit driving direction
};
WheelGeometry wheel_geometry(const WheelConfig& wheel);

}  // namespace ubersim::physics
