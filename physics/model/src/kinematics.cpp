#include "ubersim/physics/kinematics.hpp"

#include <cmath>

namespace ubersim::physics {

WheelGeometry wheel_geometry(const WheelConfig& wheel) {
  WheelGeometry g;
  g.x = wheel.distance * std::cos(wheel.angle);
  g.y = wheel.distance * std::sin(wheel.angle);
  g.dx = wheel.drive_x;
  g.dy = wheel.drive_y;
  return g;
}

WheelKinematics::WheelKinematics(const RobotTypeConfig& robot) {
  const auto n = static_cast<Eigen::Index>(robot.wheels.size());
  inverse_.resize(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    const WheelGeometry g = wheel_geometry(robot.wheels[static_cast<std::size_t>(i)]);
    inverse_(i, 0) = g.dx / robot.wheel_radius;
    inverse_(i, 1) = g.dy / robot.wheel_radius;
    inverse_(i, 2) = (g.x * g.dy - g.y * g.dx) / robot.wheel_radius;
  }
  forward_ = inverse_.completeOrthogonalDecomposition().pseudoInverse();
}

}  // namespace ubersim::physics
