#include "ubersim/ssl_bridge/realism_translation.hpp"

#include <ssl_simulation_custom_erforce_realism.pb.h>

#include <cmath>
#include <string>
#include <vector>

namespace ubersim::ssl {
namespace {

constexpr double kNanosecond = 1e-9;  // s
// The vision emulator's bounds (ubersim/vision/vision_profile.hpp, not a
// dependency of the bridge): kept equal by test_realism_translation.
constexpr double kMaxBallAreaSigma = 1e6;   // px^2
constexpr double kMaxCameraOverlap = 1000;  // m
constexpr double kMaxCameraOffset = 10;     // m

// ER-Force's field -> our parameter, or a note of what is not modelled.
void map_erforce(const RealismConfigErForce& in, const std::string& field, emulator_realism_t& out,
                 Errors& errors) {
  std::vector<std::string> invalid;
  const auto non_negative = [&](bool has, double value, const char* name) {
    if (!has) return false;
    if (std::isfinite(value) && value >= 0) return true;
    invalid.push_back(name);
    return false;
  };
  const auto probability = [&](bool has, double value, const char* name) {
    if (!non_negative(has, value, name)) return false;
    if (value <= 1) return true;
    invalid.push_back(name);
    return false;
  };
  // The vision emulator's bounds (vision_profile.hpp): beyond them a value is
  // a unit mistake, and the emulator would refuse the whole change.
  const auto bounded = [&](bool has, double value, double max, const char* name) {
    if (!non_negative(has, value, name)) return false;
    if (value <= max) return true;
    invalid.push_back(name);
    return false;
  };
  if (non_negative(in.has_stddev_ball_p(), in.stddev_ball_p(), "stddev_ball_p")) {
    out.ball_sigma_position = in.stddev_ball_p();
  }
  if (non_negative(in.has_stddev_robot_p(), in.stddev_robot_p(), "stddev_robot_p")) {
    out.robot_sigma_position = in.stddev_robot_p();
  }
  if (non_negative(in.has_stddev_robot_phi(), in.stddev_robot_phi(), "stddev_robot_phi")) {
    out.robot_sigma_orientation = in.stddev_robot_phi();
  }
  if (bounded(in.has_stddev_ball_area(), in.stddev_ball_area(), kMaxBallAreaSigma,
              "stddev_ball_area")) {
    out.ball_area_sigma = in.stddev_ball_area();  // px^2 on the reported ball area
  }
  // ER-Force: the ball is reported while at least this fraction of it is
  // visible; with invisible balls off, always (ours: while any of it is).
  const bool threshold_ok =
      probability(in.has_ball_visibility_threshold(), in.ball_visibility_threshold(),
                  "ball_visibility_threshold");
  if (in.has_enable_invisible_ball() && !in.enable_invisible_ball()) {
    out.ball_min_visible_fraction = 0;
  } else if (threshold_ok) {
    out.ball_min_visible_fraction = in.ball_visibility_threshold();
  }
  if (bounded(in.has_camera_overlap(), in.camera_overlap(), kMaxCameraOverlap, "camera_overlap")) {
    out.camera_overlap = in.camera_overlap();
  }
  if (non_negative(in.has_dribbler_ball_detections(), in.dribbler_ball_detections(),
                   "dribbler_ball_detections")) {
    out.false_ball_rate = in.dribbler_ball_detections();
  }
  if (bounded(in.has_camera_position_error(), in.camera_position_error(), kMaxCameraOffset,
              "camera_position_error")) {
    out.camera_position_error = in.camera_position_error();
  }
  if (probability(in.has_robot_command_loss(), in.robot_command_loss(), "robot_command_loss")) {
    out.command_robot_loss = in.robot_command_loss();
  }
  if (probability(in.has_robot_response_loss(), in.robot_response_loss(), "robot_response_loss")) {
    out.feedback_robot_loss = in.robot_response_loss();
  }
  if (probability(in.has_missing_ball_detections(), in.missing_ball_detections(),
                  "missing_ball_detections")) {
    out.ball_detection_probability = 1.0 - in.missing_ball_detections();
  }
  if (probability(in.has_missing_robot_detections(), in.missing_robot_detections(),
                  "missing_robot_detections")) {
    out.robot_detection_probability = 1.0 - in.missing_robot_detections();
  }
  if (non_negative(in.has_vision_delay(), static_cast<double>(in.vision_delay()), "vision_delay")) {
    out.vision_latency = static_cast<double>(in.vision_delay()) * kNanosecond;
  }
  if (non_negative(in.has_vision_processing_time(),
                   static_cast<double>(in.vision_processing_time()), "vision_processing_time")) {
    out.vision_processing_time = static_cast<double>(in.vision_processing_time()) * kNanosecond;
  }
  if (bounded(in.has_object_position_offset(), in.object_position_offset(), kMaxCameraOffset,
              "object_position_offset")) {
    out.object_position_offset = in.object_position_offset();
  }
  if (in.has_command_delay()) {
    out.command_latency = static_cast<double>(in.command_delay()) * kNanosecond;
  }
  if (!invalid.empty()) {
    std::string names;
    for (const std::string& n : invalid) names += (names.empty() ? "" : ", ") + n;
    add_error(
        errors, kErrorInvalid,
        field + ": negative, non-finite or (for a probability) above 1, not applied: " + names);
  }
}

}  // namespace

RealismTranslation translate_realism(const RealismConfig& config) {
  RealismTranslation out;
  emulator_realism_t realism = unchanged_realism();
  bool any = false;
  for (int i = 0; i < config.custom_size(); ++i) {
    const google::protobuf::Any& any_config = config.custom(i);
    const std::string field = "realism_config.custom[" + std::to_string(i) + "]";
    const std::string& url = any_config.type_url();
    const std::string type = url.substr(url.find_last_of('/') + 1);
    if (type != "RealismConfigErForce" && type != "sslsim.RealismConfigErForce") {
      add_error(out.errors, kErrorUnsupported,
                field + ": type '" + type + "' is not known to ubersim (RealismConfigErForce is)");
      continue;
    }
    RealismConfigErForce erforce;
    if (!erforce.ParseFromString(any_config.value())) {
      add_error(out.errors, kErrorMalformed, field + ": does not decode as RealismConfigErForce");
      continue;
    }
    map_erforce(erforce, field, realism, out.errors);
    // false = ER-Force's "glue the ball during dribbling": physics' perfect dribbling.
    if (erforce.has_simulate_dribbling()) out.perfect_dribbling = !erforce.simulate_dribbling();
    any = true;
  }
  if (any) out.realism = realism;
  return out;
}

}  // namespace ubersim::ssl
