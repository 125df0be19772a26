#pragma once
// A pinhole camera above the field, with SSL-Vision's radial lens distortion.
// Camera frame as in OpenCV: x along image columns, y along image rows, z
// along the optical axis. Pixel (u, v) = principal point + focal_length * d,
// where the undistorted point u = (x / z, y / z) appears at d, |u| = |d| *
// (1 + distortion * |d|^2) (SSL-Vision's model; distortion 0: ideal pinhole).
#include <Eigen/Core>
#include <optional>
#include <ubersim/camera_calibration_t.hpp>

namespace ubersim::vision {

struct CameraIntrinsics {
  double focal_length = 0;  // px
  double principal_x = 0;   // px
  double principal_y = 0;   // px
  int width = 0;            // px; 0 (with height 0): the image has no edge
  int height = 0;           // px
  double distortion = 0;    // unitless, SSL-Vision's radial distortion coefficient
};

// Rotation in the field frame: roll about x, then pitch about y, then yaw about z (rad).
Eigen::Matrix3d field_rotation(const Eigen::Vector3d& roll_pitch_yaw);

// Rotation camera -> field of an overhead camera. (0, 0, 0) looks straight
// down with image columns along field +x and rows along field -y (the image
// shows the field as a map with +y up). Then roll about field x, pitch about
// field y and yaw about field z are applied, in that order (rad).
Eigen::Matrix3d overhead_rotation(const Eigen::Vector3d& roll_pitch_yaw);

class PinholeCamera {
 public:
  PinholeCamera(const Eigen::Vector3d& position, const Eigen::Matrix3d& camera_to_field,
                const CameraIntrinsics& intrinsics);

  // Pixel of a field point; empty when the point is not in front of the camera
  // (or, with a negative distortion, beyond the radius the lens can image).
  std::optional<Eigen::Vector2d> project(const Eigen::Vector3d& field_point) const;
  // Whether a pixel lies on the image: [0, width) x [0, height); every pixel
  // when the image has no edge (width 0).
  bool in_image(const Eigen::Vector2d& pixel) const;
  // Where the ray through `pixel` meets the horizontal plane z = plane_z; empty
  // when the ray does not reach it (plane above the camera, ray parallel).
  std::optional<Eigen::Vector3d> intersect_plane(const Eigen::Vector2d& pixel,
                                                 double plane_z) const;

  const Eigen::Vector3d& position() const { return position_; }
  const Eigen::Matrix3d& camera_to_field() const { return camera_to_field_; }
  const CameraIntrinsics& intrinsics() const { return intrinsics_; }

  camera_calibration_t to_calibration(int camera_id) const;

 private:
  Eigen::Vector3d position_;
  Eigen::Matrix3d camera_to_field_;
  Eigen::Matrix3d field_to_camera_;
  CameraIntrinsics intrinsics_;
};

}  // namespace ubersim::vision
