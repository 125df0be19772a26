#include "ubersim/vision/pinhole_camera.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace ubersim::vision {
namespace {

// The distorted radius rd with ru = rd * (1 + k * rd^2) (SSL-Vision's model),
// by Newton's method from rd = ru; empty when no rd on the lens's monotonic
// part maps to ru (only with k < 0, beyond rd = 1 / sqrt(-3 k)).
std::optional<double> distorted_radius(double ru, double k) {
  if (k == 0 || ru == 0) return ru;
  if (k < 0) {
    const double rd_max = 1.0 / std::sqrt(-3.0 * k);
    if (ru > rd_max * (1.0 + k * rd_max * rd_max)) return std::nullopt;
  }
  double rd = ru;
  for (int i = 0; i < 50; ++i) {
    const double f = rd * (1.0 + k * rd * rd) - ru;
    const double df = 1.0 + 3.0 * k * rd * rd;
    if (df <= 0) return std::nullopt;
    const double step = f / df;
    rd -= step;
    if (std::abs(step) <= 1e-15 * (1.0 + std::abs(rd))) break;
  }
  return rd;
}

}  // namespace

Eigen::Matrix3d field_rotation(const Eigen::Vector3d& roll_pitch_yaw) {
  return (Eigen::AngleAxisd(roll_pitch_yaw.z(), Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(roll_pitch_yaw.y(), Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll_pitch_yaw.x(), Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

Eigen::Matrix3d overhead_rotation(const Eigen::Vector3d& roll_pitch_yaw) {
  // Camera x -> field +x, camera y (rows) -> field -y, camera z (optical axis) -> field -z.
  const Eigen::Matrix3d straight_down = Eigen::Vector3d(1, -1, -1).asDiagonal();
  return field_rotation(roll_pitch_yaw) * straight_down;
}

PinholeCamera::PinholeCamera(const Eigen::Vector3d& position,
                             const Eigen::Matrix3d& camera_to_field,
                             const CameraIntrinsics& intrinsics)
    : position_(position),
      camera_to_field_(camera_to_field),
      field_to_camera_(camera_to_field.transpose()),
      intrinsics_(intrinsics) {}

std::optional<Eigen::Vector2d> PinholeCamera::project(const Eigen::Vector3d& field_point) const {
  const Eigen::Vector3d p = field_to_camera_ * (field_point - position_);
  if (p.z() <= 1e-9) return std::nullopt;
  Eigen::Vector2d image_point(p.x() / p.z(), p.y() / p.z());
  if (intrinsics_.distortion != 0) {
    const double ru = image_point.norm();
    const auto rd = distorted_radius(ru, intrinsics_.distortion);
    if (!rd) return std::nullopt;
    if (ru > 0) image_point *= *rd / ru;
  }
  return Eigen::Vector2d(intrinsics_.principal_x + intrinsics_.focal_length * image_point.x(),
                         intrinsics_.principal_y + intrinsics_.focal_length * image_point.y());
}

bool PinholeCamera::in_image(const Eigen::Vector2d& pixel) const {
  if (intrinsics_.width <= 0 || intrinsics_.height <= 0) return true;  // no edge
  return pixel.x() >= 0 && pixel.x() < intrinsics_.width && pixel.y() >= 0 &&
         pixel.y() < intrinsics_.height;
}

std::optional<Eigen::Vector3d> PinholeCamera::intersect_plane(const Eigen::Vector2d& pixel,
                                                              double plane_z) const {
  Eigen::Vector2d image_point((pixel.x() - intrinsics_.principal_x) / intrinsics_.focal_length,
                              (pixel.y() - intrinsics_.principal_y) / intrinsics_.focal_length);
  // Undistorted as SSL-Vision does it: ru = rd * (1 + k * rd^2).
  image_point *= 1.0 + intrinsics_.distortion * image_point.squaredNorm();
  const Eigen::Vector3d ray =
      camera_to_field_ * Eigen::Vector3d(image_point.x(), image_point.y(), 1.0);
  if (std::abs(ray.z()) < 1e-12) return std::nullopt;
  const double s = (plane_z - position_.z()) / ray.z();
  if (s <= 0) return std::nullopt;
  return Eigen::Vector3d(position_ + s * ray);
}

camera_calibration_t PinholeCamera::to_calibration(int camera_id) const {
  camera_calibration_t c{};
  c.camera_id = camera_id;
  c.focal_length = intrinsics_.focal_length;
  c.principal_x = intrinsics_.principal_x;
  c.principal_y = intrinsics_.principal_y;
  c.image_width = intrinsics_.width;
  c.image_height = intrinsics_.height;
  c.distortion = intrinsics_.distortion;
  for (int i = 0; i < 3; ++i) c.position[i] = position_[i];
  Eigen::Quaterniond q(camera_to_field_);
  q.normalize();
  if (q.w() < 0) q.coeffs() *= -1;  // one of the two equal quaternions, w >= 0
  c.orientation[0] = q.w();
  c.orientation[1] = q.x();
  c.orientation[2] = q.y();
  c.orientation[3] = q.z();
  return c;
}

}  // namespace ubersim::vision
