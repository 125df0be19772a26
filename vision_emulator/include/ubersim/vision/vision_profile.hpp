#pragma once
// A vision emulator profile (config/vision/*.cfg) read into plain data: frame
// rate, latency, noise, detection and confidence model, and N pinhole cameras
// with their true pose and the calibration error the vision system believes.
// Keys and units are listed in config/vision/cmdragons02.cfg and the notes.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "ubersim/config.hpp"

namespace ubersim::vision {

// Bounds a profile's values keep, read from a config file or changed at run
// time (EMULATOR_REALISM): beyond them a value is a unit mistake or garbage.
inline constexpr double kMaxFrameRate = 1000.0;      // Hz
inline constexpr double kMaxSigma = 1.0;             // m
inline constexpr double kMaxLatency = 10.0;          // s
inline constexpr double kMaxCameraOffset = 10.0;     // m: camera position error, object offset
inline constexpr double kMaxCameraOverlap = 1000.0;  // m (100 m already lets every camera see all)
inline constexpr double kMaxBallAreaSigma = 1e6;     // px^2
inline constexpr double kMaxDistortion = 10.0;       // unitless; real lenses are within +-1
// ER-Force's camera overlap while no realism sets one: the region rule for
// cameras given at run time (VISION_CAMERAS), as its simulator starts.
inline constexpr double kErForceDefaultCameraOverlap = 0.3;  // m

struct CameraProfile {
  int id = 0;
  double frame_rate = 0;  // Hz
  double phase = 0;       // s, captures at phase + n / frame_rate (sim time)
  // Timing of this camera's frames (the profile's LATENCY ... unless overridden).
  double latency = 0;          // s, capture -> publication on VISION
  double latency_jitter = 0;   // s, standard deviation added to the latency
  double processing_time = 0;  // s, t_sent - t_capture
  // True pose: centre (m) and roll, pitch, yaw (rad) relative to looking
  // straight down with image columns along field +x and rows along field -y.
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d roll_pitch_yaw = Eigen::Vector3d::Zero();
  double focal_length = 0;  // px
  int image_width = 0;      // px
  int image_height = 0;     // px
  double principal_x = 0;   // px
  double principal_y = 0;   // px
  double distortion = 0;    // unitless, SSL-Vision's radial distortion (0: ideal pinhole)
  // Calibration error: what the vision system believes minus the truth.
  Eigen::Vector3d position_error = Eigen::Vector3d::Zero();        // m
  Eigen::Vector3d roll_pitch_yaw_error = Eigen::Vector3d::Zero();  // rad
  double focal_length_error = 0;                                   // px

  double period() const { return 1.0 / frame_rate; }
};

struct VisionProfile {
  std::string name;
  std::uint64_t seed = 0;

  // Defaults for every camera's timing (CAMERA_<k>_LATENCY ... override them).
  double latency = 0;          // s, capture -> publication on VISION
  double latency_jitter = 0;   // s, standard deviation added to the latency
  double processing_time = 0;  // s, t_sent - t_capture
  double geometry_period = 1;  // s of wall-clock time between VISION_GEOMETRY messages

  double robot_sigma_x = 0;            // m
  double robot_sigma_y = 0;            // m
  double robot_sigma_orientation = 0;  // rad
  double ball_sigma_x = 0;             // m
  double ball_sigma_y = 0;             // m

  double robot_detection_probability = 1;  // per robot per camera frame
  double ball_detection_probability = 1;   // per ball per camera frame
  double robot_confidence = 1;             // mean confidence of a robot detection
  double ball_confidence = 1;              // mean of a fully visible ball (x visible fraction)
  double confidence_sigma = 0;             // spread of every confidence
  double false_ball_rate = 0;              // 1/s per robot in a camera's view
  double false_ball_spread = 0;            // m, around the point in front of the dribbler
  double false_ball_confidence = 0;        // mean confidence of a false ball
  double ball_min_visible_fraction = 0;    // a ball less visible than this is not reported
  double ball_radius = 0.0215;             // m, until SIM_GEOMETRY names the ball in use

  // ER-Force's camera model (its realism fields of the same names):
  // < 0: each camera sees what its image shows. >= 0: in addition a camera
  // sees only its region of the field (the points nearer to it, in Manhattan
  // distance on the ground, than to any other camera) widened by this much.
  double camera_overlap = -1;  // m
  // Each camera's reported centre (VISION_GEOMETRY) is off by this much in
  // ER-Force's direction; the field mapping stays right, so only what is
  // above the ground shifts (by the error x height / camera height).
  double camera_position_error = 0;  // m
  // Each camera's detections shift this far, away from the field centre
  // towards the camera (a systematic error per camera).
  double object_position_offset = 0;  // m
  double ball_area_sigma = 0;         // px^2, Gaussian noise on a ball's reported area

  // FRAME_NUMBERS = shared: the frames the cameras capture at one simulation
  // step carry one frame number (a counter of such steps), as grSim numbers
  // its cameras' frames; per_camera (the default): each camera counts its own
  // frames, as SSL-Vision does.
  bool shared_frame_numbers = false;

  std::vector<CameraProfile> cameras;
};

// Reads every key of a profile (and rejects any other). Throws ConfigError.
VisionProfile load_vision_profile(const ConfigFile& config, const std::string& name);
// `name` is a profile name under <config_dir>/vision/ or a path to a .cfg file.
VisionProfile load_vision_profile(const std::string& config_dir, const std::string& name);

}  // namespace ubersim::vision
