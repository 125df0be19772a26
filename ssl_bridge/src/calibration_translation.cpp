#include "ubersim/ssl_bridge/calibration_translation.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "ubersim/ssl_bridge/units.hpp"

namespace ubersim::ssl {
namespace {

constexpr int kMaxCameras = 64;
constexpr std::uint32_t kMaxCameraId = 255;
constexpr double kMaxPixels = 1e5;          // px
constexpr double kMaxDistortion = 10;       // unitless; real lenses are within +-1
constexpr double kMaxCameraDistance = 100;  // m
constexpr double kMinCameraHeight = 0.5;    // m
constexpr double kUnitTolerance = 1e-3;     // |q| - 1 of a rotation
constexpr double kCentreTolerance = 0.05;   // m between -R^T t and the derived position
constexpr double kMinDownwardAxis = 0.1;    // cos(84 deg): the axis may tilt 84 deg at most

// Camera -> field rotation of a camera looking straight down, image columns
// along field +x and rows along field -y (quaternion w, x, y, z).
constexpr double kStraightDown[4] = {0, 1, 0, 0};

struct Camera {
  camera_calibration_t calibration{};
  std::vector<std::string> invalid;  // names of the fields that are not valid
};

// The SSL rotation (field -> camera) as a quaternion when it is a rotation.
std::optional<Eigen::Quaterniond> field_to_camera(const SSL_GeometryCameraCalibration& c) {
  const Eigen::Quaterniond q(c.q3(), c.q0(), c.q1(), c.q2());  // w, x, y, z
  if (!std::isfinite(q.norm()) || std::abs(q.norm() - 1) > kUnitTolerance) return std::nullopt;
  return q.normalized();
}

// The camera centre SSL-Vision's extrinsics give: -R^T t (m).
Eigen::Vector3d extrinsic_centre(const Eigen::Quaterniond& field_to_camera,
                                 const SSL_GeometryCameraCalibration& c) {
  const Eigen::Vector3d t(mm_to_m(c.tx()), mm_to_m(c.ty()), mm_to_m(c.tz()));
  return -(field_to_camera.conjugate() * t);
}

Camera translate_one(const SSL_GeometryCameraCalibration& c) {
  Camera out;
  camera_calibration_t& cal = out.calibration;
  const auto check = [&](bool ok, const char* name) {
    if (!ok) out.invalid.push_back(name);
  };
  check(c.camera_id() <= kMaxCameraId, "camera_id (0..255)");
  cal.camera_id = static_cast<std::int32_t>(std::min(c.camera_id(), kMaxCameraId));
  check(std::isfinite(c.focal_length()) && c.focal_length() >= 1 && c.focal_length() <= kMaxPixels,
        "focal_length (1..1e5 px)");
  check(std::isfinite(c.principal_point_x()) && std::abs(c.principal_point_x()) <= kMaxPixels,
        "principal_point_x");
  check(std::isfinite(c.principal_point_y()) && std::abs(c.principal_point_y()) <= kMaxPixels,
        "principal_point_y");
  check(std::isfinite(c.distortion()) && std::abs(c.distortion()) <= kMaxDistortion,
        "distortion (-10..10)");
  for (float v : {c.q0(), c.q1(), c.q2(), c.q3(), c.tx(), c.ty(), c.tz()}) {
    if (!std::isfinite(v)) {
      out.invalid.push_back("q0..q3, tx..tz (not finite)");
      break;
    }
  }
  cal.focal_length = c.focal_length();
  cal.principal_x = c.principal_point_x();
  cal.principal_y = c.principal_point_y();
  cal.distortion = c.distortion();
  // Without both sizes the image has no edge: the camera's region decides (ER-Force).
  if (c.has_pixel_image_width() && c.has_pixel_image_height()) {
    check(c.pixel_image_width() >= 1 && c.pixel_image_width() <= kMaxPixels,
          "pixel_image_width (1..1e5 px)");
    check(c.pixel_image_height() >= 1 && c.pixel_image_height() <= kMaxPixels,
          "pixel_image_height (1..1e5 px)");
    cal.image_width =
        static_cast<std::int32_t>(std::min<double>(c.pixel_image_width(), kMaxPixels));
    cal.image_height =
        static_cast<std::int32_t>(std::min<double>(c.pixel_image_height(), kMaxPixels));
  }

  const auto rotation = field_to_camera(c);
  const int derived = int{c.has_derived_camera_world_tx()} + int{c.has_derived_camera_world_ty()} +
                      int{c.has_derived_camera_world_tz()};
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  if (derived == 3) {  // what the ER-Force simulator places its cameras by
    centre =
        Eigen::Vector3d(mm_to_m(c.derived_camera_world_tx()), mm_to_m(c.derived_camera_world_ty()),
                        mm_to_m(c.derived_camera_world_tz()));
  } else if (derived == 0 && rotation) {
    centre = extrinsic_centre(*rotation, c);
  } else {
    out.invalid.push_back(derived == 0
                              ? "derived_camera_world_tx/ty/tz unset and q0..q3 not a rotation "
                                "(no camera position)"
                              : "derived_camera_world_tx/ty/tz (only some set)");
  }
  check(centre.allFinite() && std::abs(centre.x()) <= kMaxCameraDistance &&
            std::abs(centre.y()) <= kMaxCameraDistance && centre.z() >= kMinCameraHeight &&
            centre.z() <= kMaxCameraDistance,
        "camera position (within 100 m, at least 0.5 m above the field)");
  for (int i = 0; i < 3; ++i) cal.position[i] = centre[i];

  // The given rotation where it describes this camera looking down; else straight down.
  std::copy(std::begin(kStraightDown), std::end(kStraightDown), std::begin(cal.orientation));
  if (rotation && out.invalid.empty()) {
    const Eigen::Quaterniond camera_to_field = rotation->conjugate();
    const bool looks_down = (camera_to_field * Eigen::Vector3d::UnitZ()).z() <= -kMinDownwardAxis;
    const bool same_centre = (extrinsic_centre(*rotation, c) - centre).norm() <= kCentreTolerance;
    if (looks_down && same_centre) {
      Eigen::Quaterniond q = camera_to_field;
      if (q.w() < 0) q.coeffs() *= -1;
      cal.orientation[0] = q.w();
      cal.orientation[1] = q.x();
      cal.orientation[2] = q.y();
      cal.orientation[3] = q.z();
    }
  }
  return out;
}

}  // namespace

CalibrationTranslation translate_calibrations(const SSL_GeometryData& geometry) {
  CalibrationTranslation out;
  if (geometry.calib_size() == 0) return out;
  if (geometry.calib_size() > kMaxCameras) {
    add_error(out.errors, kErrorInvalid,
              "geometry.calib: " + std::to_string(geometry.calib_size()) +
                  " cameras, at most 64; the cameras stay as they are");
    return out;
  }
  vision_cameras_t set{};
  std::set<std::int32_t> ids;
  for (int i = 0; i < geometry.calib_size(); ++i) {
    Camera camera = translate_one(geometry.calib(i));
    if (camera.invalid.empty() && !ids.insert(camera.calibration.camera_id).second) {
      camera.invalid.push_back("camera_id (used twice)");
    }
    if (!camera.invalid.empty()) {
      std::string names;
      for (const std::string& n : camera.invalid) names += (names.empty() ? "" : ", ") + n;
      add_error(out.errors, kErrorInvalid,
                "geometry.calib[" + std::to_string(i) + "]: not valid: " + names +
                    "; the cameras stay as they are");
      continue;
    }
    set.cameras.push_back(camera.calibration);
  }
  if (!out.errors.empty()) return out;  // a camera set is applied whole or not at all
  set.num_cameras = static_cast<std::int32_t>(set.cameras.size());
  out.cameras = set;
  return out;
}

}  // namespace ubersim::ssl
