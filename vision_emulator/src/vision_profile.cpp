#include "ubersim/vision/vision_profile.hpp"

#include <cmath>
#include <sstream>

#include "ubersim/angles.hpp"
#include "ubersim/config_paths.hpp"
#include "ubersim/vision/pinhole_camera.hpp"

namespace ubersim::vision {
namespace {

constexpr double kMaxJitter = 1.0;  // s

std::string camera_key(int index, const char* suffix) {
  return "CAMERA_" + std::to_string(index) + "_" + suffix;
}

Eigen::Vector3d vector3(const ConfigFile& config, const std::string& key, double scale = 1.0) {
  const auto values = config.reals(key, 3);
  return Eigen::Vector3d(values[0], values[1], values[2]) * scale;
}

Eigen::Vector3d optional_vector3(const ConfigFile& config, const std::string& key,
                                 double scale = 1.0) {
  return config.has(key) ? vector3(config, key, scale) : Eigen::Vector3d::Zero();
}

void require_in(const ConfigFile& config, const std::string& key, double value, double min,
                double max) {
  if (value >= min && value <= max) return;
  std::ostringstream what;
  what << "expected values in [" << min << ", " << max << "], got " << value;
  config.fail(key, what.str());
}

// A camera's optional override of a profile-wide value.
double camera_real_in(const ConfigFile& config, const std::string& key, double fallback, double min,
                      double max) {
  return config.has(key) ? config.real_in(key, min, max) : fallback;
}

CameraProfile load_camera(const ConfigFile& config, int index, const VisionProfile& defaults,
                          double default_frame_rate) {
  CameraProfile c;
  c.id = index;
  c.frame_rate = camera_real_in(config, camera_key(index, "FRAME_RATE"), default_frame_rate, 0.1,
                                kMaxFrameRate);
  c.latency =
      camera_real_in(config, camera_key(index, "LATENCY"), defaults.latency, 0.0, kMaxLatency);
  c.latency_jitter = camera_real_in(config, camera_key(index, "LATENCY_JITTER"),
                                    defaults.latency_jitter, 0.0, kMaxJitter);
  const std::string processing_key = camera_key(index, "PROCESSING_TIME");
  c.processing_time =
      camera_real_in(config, processing_key, defaults.processing_time, 0.0, kMaxLatency);
  if (c.processing_time > c.latency) {
    config.fail(
        config.has(processing_key) ? processing_key : camera_key(index, "LATENCY"),
        "camera " + std::to_string(index) + ": its processing time must not exceed its latency");
  }
  const std::string phase_key = camera_key(index, "PHASE");
  c.phase = config.real(phase_key);
  if (c.phase < 0 || c.phase >= c.period()) {
    config.fail(phase_key, "expected a phase in [0, frame period = " + std::to_string(c.period()) +
                               " s), got " + std::to_string(c.phase));
  }

  const std::string position_key = camera_key(index, "POSITION");
  c.position = vector3(config, position_key);
  require_in(config, position_key, std::abs(c.position.x()), 0, 100);
  require_in(config, position_key, std::abs(c.position.y()), 0, 100);
  // A camera must hang above every robot and ball it is to see.
  require_in(config, position_key, c.position.z(), 0.5, 100);

  const std::string orientation_key = camera_key(index, "ORIENTATION_DEG");
  c.roll_pitch_yaw = vector3(config, orientation_key, kDegToRad);
  const Eigen::Vector3d axis = overhead_rotation(c.roll_pitch_yaw).col(2);
  if (axis.z() > -0.1) {
    config.fail(orientation_key,
                "the camera must look down at the field (optical axis at most "
                "84 deg from straight down)");
  }

  c.focal_length = config.real_in(camera_key(index, "FOCAL_LENGTH"), 1.0, 1e5);
  const std::string size_key = camera_key(index, "IMAGE_SIZE");
  const auto size = config.integers(size_key, 2);
  require_in(config, size_key, static_cast<double>(size[0]), 1, 100000);
  require_in(config, size_key, static_cast<double>(size[1]), 1, 100000);
  c.image_width = static_cast<int>(size[0]);
  c.image_height = static_cast<int>(size[1]);
  const std::string principal_key = camera_key(index, "PRINCIPAL_POINT");
  if (config.has(principal_key)) {
    const auto principal = config.reals(principal_key, 2);
    require_in(config, principal_key, principal[0], 0, c.image_width);
    require_in(config, principal_key, principal[1], 0, c.image_height);
    c.principal_x = principal[0];
    c.principal_y = principal[1];
  } else {
    c.principal_x = c.image_width / 2.0;
    c.principal_y = c.image_height / 2.0;
  }

  c.distortion =
      camera_real_in(config, camera_key(index, "DISTORTION"), 0.0, -kMaxDistortion, kMaxDistortion);

  const std::string position_error_key = camera_key(index, "CALIBRATION_ERROR_POSITION");
  c.position_error = optional_vector3(config, position_error_key);
  if (c.position_error.norm() > 10) config.fail(position_error_key, "expected at most 10 m");
  const std::string orientation_error_key = camera_key(index, "CALIBRATION_ERROR_ORIENTATION_DEG");
  c.roll_pitch_yaw_error = optional_vector3(config, orientation_error_key, kDegToRad);
  if (c.roll_pitch_yaw_error.cwiseAbs().maxCoeff() > 45 * kDegToRad) {
    config.fail(orientation_error_key, "expected at most 45 deg per angle");
  }
  const std::string focal_error_key = camera_key(index, "CALIBRATION_ERROR_FOCAL_LENGTH");
  c.focal_length_error = config.real(focal_error_key, 0.0);
  if (c.focal_length + c.focal_length_error < 1.0) {
    config.fail(focal_error_key, "the believed focal length must stay above 1 px");
  }
  return c;
}

}  // namespace

VisionProfile load_vision_profile(const ConfigFile& config, const std::string& name) {
  VisionProfile p;
  p.name = name;
  const std::int64_t seed = config.integer("SEED");
  if (seed < 0) config.fail("SEED", "expected an integer >= 0");
  p.seed = static_cast<std::uint64_t>(seed);

  const double frame_rate = config.real_in("FRAME_RATE", 0.1, kMaxFrameRate);
  p.latency = config.real_in("LATENCY", 0.0, kMaxLatency);
  p.latency_jitter = config.real_in("LATENCY_JITTER", 0.0, kMaxJitter);
  p.processing_time = config.real_in("PROCESSING_TIME", 0.0, p.latency);
  p.geometry_period = config.real_in("GEOMETRY_PERIOD", 0.05, 3600.0);

  p.robot_sigma_x = config.real_in("ROBOT_SIGMA_X", 0.0, kMaxSigma);
  p.robot_sigma_y = config.real_in("ROBOT_SIGMA_Y", 0.0, kMaxSigma);
  p.robot_sigma_orientation = config.real_in("ROBOT_SIGMA_ORIENTATION", 0.0, M_PI);
  p.ball_sigma_x = config.real_in("BALL_SIGMA_X", 0.0, kMaxSigma);
  p.ball_sigma_y = config.real_in("BALL_SIGMA_Y", 0.0, kMaxSigma);

  p.robot_detection_probability = config.real_in("ROBOT_DETECTION_PROBABILITY", 0.0, 1.0);
  p.ball_detection_probability = config.real_in("BALL_DETECTION_PROBABILITY", 0.0, 1.0);
  p.robot_confidence = config.real_in("ROBOT_CONFIDENCE", 0.0, 1.0);
  p.ball_confidence = config.real_in("BALL_CONFIDENCE", 0.0, 1.0);
  p.confidence_sigma = config.real_in("CONFIDENCE_SIGMA", 0.0, 1.0);
  p.false_ball_rate = config.real_in("FALSE_BALL_RATE", 0.0, kMaxFrameRate);
  p.false_ball_spread = config.real_in("FALSE_BALL_SPREAD", 0.0, kMaxSigma);
  p.false_ball_confidence = config.real_in("FALSE_BALL_CONFIDENCE", 0.0, 1.0);
  p.ball_min_visible_fraction = config.real_in("BALL_MIN_VISIBLE_FRACTION", 0.0, 1.0);
  p.ball_radius = config.real_in("BALL_RADIUS", 0.005, 0.2);
  p.camera_overlap = camera_real_in(config, "CAMERA_OVERLAP", -1.0, 0.0, kMaxCameraOverlap);
  p.camera_position_error =
      camera_real_in(config, "CAMERA_POSITION_ERROR", 0.0, 0.0, kMaxCameraOffset);
  p.object_position_offset =
      camera_real_in(config, "OBJECT_POSITION_OFFSET", 0.0, 0.0, kMaxCameraOffset);
  p.ball_area_sigma = camera_real_in(config, "BALL_AREA_SIGMA", 0.0, 0.0, kMaxBallAreaSigma);

  const std::string numbering = config.string("FRAME_NUMBERS", "per_camera");
  if (numbering != "per_camera" && numbering != "shared") {
    config.fail("FRAME_NUMBERS", "expected per_camera or shared, got '" + numbering + "'");
  }
  p.shared_frame_numbers = numbering == "shared";

  const std::int64_t count = config.integer_in("CAMERA_COUNT", 1, 64);
  for (int index = 0; index < count; ++index) {
    p.cameras.push_back(load_camera(config, index, p, frame_rate));
  }
  // Keys of cameras beyond CAMERA_COUNT are reported here as unknown keys.
  config.require_all_used();
  return p;
}

VisionProfile load_vision_profile(const std::string& config_dir, const std::string& name) {
  const auto path = resolve_config(config_dir, "vision", name);
  return load_vision_profile(ConfigFile::load(path), path.stem().string());
}

}  // namespace ubersim::vision
