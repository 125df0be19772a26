// Run-time realism changes (EMULATOR_REALISM), e.g. an SSL simulation
// protocol realism preset: noise, detection probabilities, false balls, ball
// occlusion, timing and ER-Force's camera model (overlap, position error,
// object offset, ball area noise) change between captures, without a restart.
// The cameras themselves change on VISION_CAMERAS (vision_cameras.cpp).
#include <cmath>
#include <initializer_list>

#include "ubersim/vision/vision_emulator.hpp"

namespace ubersim::vision {
namespace {

// < 0 means "unchanged"; NaN or infinity is a bad message.
bool given(double value) {
  return value >= 0;
}

}  // namespace

std::string VisionEmulator::apply_realism(const emulator_realism_t& r) {
  for (double v :
       {r.robot_sigma_position, r.robot_sigma_orientation, r.ball_sigma_position,
        r.robot_detection_probability, r.ball_detection_probability, r.false_ball_rate,
        r.ball_min_visible_fraction, r.vision_latency, r.vision_processing_time, r.ball_area_sigma,
        r.camera_overlap, r.camera_position_error, r.object_position_offset}) {
    if (!std::isfinite(v)) return "a value is not finite";
  }
  for (double p :
       {r.robot_detection_probability, r.ball_detection_probability, r.ball_min_visible_fraction}) {
    if (p > 1) return "a probability or fraction above 1";
  }
  if (r.vision_latency > kMaxLatency || r.vision_processing_time > kMaxLatency) {
    return "a time above 10 s";
  }
  // Found by fuzz_lcm_emulators: a noise of 1e307 m made frames with infinite positions.
  if (r.robot_sigma_position > kMaxSigma || r.ball_sigma_position > kMaxSigma) {
    return "a position noise above 1 m";
  }
  if (r.robot_sigma_orientation > M_PI) return "an orientation noise above pi";
  if (r.false_ball_rate > kMaxFrameRate) return "a false ball rate above 1000 per second";
  if (r.camera_overlap > kMaxCameraOverlap) return "a camera overlap above 1000 m";
  if (r.camera_position_error > kMaxCameraOffset || r.object_position_offset > kMaxCameraOffset) {
    return "a camera position error or object offset above 10 m";
  }
  if (r.ball_area_sigma > kMaxBallAreaSigma) return "a ball area noise above 1e6 px^2";
  VisionProfile& p = profile_;
  if (given(r.robot_sigma_position)) p.robot_sigma_x = p.robot_sigma_y = r.robot_sigma_position;
  if (given(r.robot_sigma_orientation)) p.robot_sigma_orientation = r.robot_sigma_orientation;
  if (given(r.ball_sigma_position)) p.ball_sigma_x = p.ball_sigma_y = r.ball_sigma_position;
  if (given(r.robot_detection_probability)) {
    p.robot_detection_probability = r.robot_detection_probability;
  }
  if (given(r.ball_detection_probability)) {
    p.ball_detection_probability = r.ball_detection_probability;
  }
  if (given(r.false_ball_rate)) p.false_ball_rate = r.false_ball_rate;
  if (given(r.ball_min_visible_fraction)) {
    p.ball_min_visible_fraction = r.ball_min_visible_fraction;
  }
  if (given(r.ball_area_sigma)) p.ball_area_sigma = r.ball_area_sigma;
  if (given(r.camera_overlap)) p.camera_overlap = r.camera_overlap;
  if (given(r.camera_position_error)) p.camera_position_error = r.camera_position_error;
  if (given(r.object_position_offset)) p.object_position_offset = r.object_position_offset;
  for (Camera& camera : cameras_) {
    if (given(r.vision_latency)) camera.timing.latency = r.vision_latency;
    if (given(r.vision_processing_time)) camera.timing.processing_time = r.vision_processing_time;
    // A frame cannot be sent before its processing is done.
    camera.timing.processing_time = std::min(camera.timing.processing_time, camera.timing.latency);
    camera.detector.set_model(p, camera.timing);
  }
  update_regions();
  return "";
}

}  // namespace ubersim::vision
