// A new camera set at run time (VISION_CAMERAS), e.g. the camera calibrations
// an SSL client's geometry carries. Every number is checked before anything
// changes: a set with one bad camera is refused whole.
#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <set>
#include <string>

#include "ubersim/vision/pinhole_camera.hpp"
#include "ubersim/vision/vision_emulator.hpp"

namespace ubersim::vision {
namespace {

constexpr std::size_t kMaxCameras = 64;
constexpr int kMaxCameraId = 255;
constexpr double kMaxCameraDistance = 100;  // m from the field centre, as a profile allows
constexpr double kMinCameraHeight = 0.5;    // m: above every robot and ball
constexpr double kMaxPixels = 1e5;          // px: focal length, principal point, image size
constexpr double kUnitTolerance = 1e-3;     // |q| - 1 of a rotation quaternion

bool finite(std::initializer_list<double> values) {
  for (double v : values) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

// Why calibration `c` cannot be a camera, or "".
std::string camera_problem(const camera_calibration_t& c) {
  if (c.camera_id < 0 || c.camera_id > kMaxCameraId) return "a camera id outside 0..255";
  if (!finite({c.focal_length, c.principal_x, c.principal_y, c.distortion, c.position[0],
               c.position[1], c.position[2], c.orientation[0], c.orientation[1], c.orientation[2],
               c.orientation[3]})) {
    return "a value that is not finite";
  }
  if (c.focal_length < 1 || c.focal_length > kMaxPixels) return "a focal length outside 1..1e5 px";
  if (std::abs(c.principal_x) > kMaxPixels || std::abs(c.principal_y) > kMaxPixels) {
    return "a principal point beyond 1e5 px";
  }
  const bool no_edge = c.image_width == 0 && c.image_height == 0;
  if (!no_edge && (c.image_width < 1 || c.image_height < 1 || c.image_width > kMaxPixels ||
                   c.image_height > kMaxPixels)) {
    return "an image size outside 1..1e5 px (or 0 x 0: no edge)";
  }
  if (std::abs(c.distortion) > kMaxDistortion) return "a distortion beyond +-10";
  if (std::abs(c.position[0]) > kMaxCameraDistance ||
      std::abs(c.position[1]) > kMaxCameraDistance || c.position[2] < kMinCameraHeight ||
      c.position[2] > kMaxCameraDistance) {
    return "a camera position beyond 100 m or below 0.5 m height";
  }
  const Eigen::Quaterniond q(c.orientation[0], c.orientation[1], c.orientation[2],
                             c.orientation[3]);
  if (std::abs(q.norm() - 1) > kUnitTolerance)
    return "an orientation that is not a unit quaternion";
  // As a profile requires: the optical axis at most 84 deg from straight down.
  if ((q.normalized().toRotationMatrix() * Eigen::Vector3d::UnitZ()).z() > -0.1) {
    return "a camera that does not look down at the field";
  }
  return "";
}

// The camera's pose and lens as a profile camera; its timing is `timing`'s.
CameraProfile camera_profile(const camera_calibration_t& c, const CameraProfile& timing) {
  CameraProfile camera = timing;
  camera.id = c.camera_id;
  camera.position = Eigen::Vector3d(c.position[0], c.position[1], c.position[2]);
  // overhead_rotation(rpy) = field_rotation(rpy) * diag(1, -1, -1); field_rotation is
  // Rz(yaw) Ry(pitch) Rx(roll), whose angles eulerAngles(2, 1, 0) gives back.
  const Eigen::Matrix3d camera_to_field =
      Eigen::Quaterniond(c.orientation[0], c.orientation[1], c.orientation[2], c.orientation[3])
          .normalized()
          .toRotationMatrix();
  const Eigen::Matrix3d field_rotation =
      camera_to_field * Eigen::Vector3d(1, -1, -1).asDiagonal().toDenseMatrix();
  const Eigen::Vector3d yaw_pitch_roll = field_rotation.eulerAngles(2, 1, 0);
  camera.roll_pitch_yaw =
      Eigen::Vector3d(yaw_pitch_roll.z(), yaw_pitch_roll.y(), yaw_pitch_roll.x());
  camera.focal_length = c.focal_length;
  camera.principal_x = c.principal_x;
  camera.principal_y = c.principal_y;
  camera.image_width = c.image_width;
  camera.image_height = c.image_height;
  camera.distortion = c.distortion;
  // The vision system believes the calibration it was given.
  camera.position_error = Eigen::Vector3d::Zero();
  camera.roll_pitch_yaw_error = Eigen::Vector3d::Zero();
  camera.focal_length_error = 0;
  return camera;
}

}  // namespace

std::string VisionEmulator::apply_cameras(const vision_cameras_t& set) {
  const auto refuse = [&](const std::string& why) {
    ++stats_.camera_sets_invalid;
    return why;
  };
  if (set.num_cameras < 1 || static_cast<std::size_t>(set.num_cameras) > kMaxCameras ||
      set.cameras.size() != static_cast<std::size_t>(set.num_cameras)) {
    return refuse("a camera count outside 1..64");
  }
  std::set<int> ids;
  for (const camera_calibration_t& c : set.cameras) {
    const std::string problem = camera_problem(c);
    if (!problem.empty()) return refuse("camera " + std::to_string(c.camera_id) + ": " + problem);
    if (!ids.insert(c.camera_id).second) {
      return refuse("camera id " + std::to_string(c.camera_id) + " twice");
    }
  }

  // New cameras capture with the first camera's rate, phase and timing as it is now.
  const CameraProfile first_timing = cameras_.front().timing;
  std::map<int, Camera> kept;
  for (Camera& camera : cameras_) {
    if (ids.count(camera.detector.id()) != 0) {
      kept.emplace(camera.detector.id(), std::move(camera));
    } else {
      stats_.frames_dropped_with_camera += camera.pending.size();
    }
  }
  std::vector<Camera> cameras;
  cameras.reserve(set.cameras.size());
  for (const camera_calibration_t& c : set.cameras) {
    const auto old = kept.find(c.camera_id);
    const CameraProfile& timing = old != kept.end() ? old->second.timing : first_timing;
    const CameraProfile profile = camera_profile(c, timing);
    if (old == kept.end()) {
      cameras.push_back(make_camera(profile));
      continue;
    }
    // Same id: the same camera counter, schedule, pending frames and random
    // streams, with the new pose, lens and the current detection model.
    Camera camera = std::move(old->second);
    CameraDetector detector(profile, profile_, profile_.seed);
    detector.continue_streams_of(camera.detector);
    camera.detector = std::move(detector);
    camera.timing = profile;
    cameras.push_back(std::move(camera));
  }
  cameras_ = std::move(cameras);
  // ER-Force decides which camera sees what by regions; so do cameras given this way.
  if (profile_.camera_overlap < 0) profile_.camera_overlap = kErForceDefaultCameraOverlap;
  update_regions();
  ++stats_.camera_sets_applied;
  return "";
}

}  // namespace ubersim::vision
