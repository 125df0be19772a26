#pragma once
// emulator_realism_t's convention: a value below 0 leaves that parameter as
// the profile (or an earlier change) set it. The one place that spells out
// "change nothing", for the SSL bridge and the tests.
#include <ubersim/emulator_realism_t.hpp>

namespace ubersim {

// Every parameter < 0: a realism change that changes nothing (fill in the rest).
inline emulator_realism_t unchanged_realism() {
  emulator_realism_t r{};
  r.robot_sigma_position = r.robot_sigma_orientation = r.ball_sigma_position = -1;
  r.robot_detection_probability = r.ball_detection_probability = -1;
  r.false_ball_rate = r.ball_min_visible_fraction = -1;
  r.vision_latency = r.vision_processing_time = -1;
  r.command_latency = r.command_robot_loss = r.feedback_robot_loss = -1;
  r.ball_area_sigma = r.camera_overlap = r.camera_position_error = r.object_position_offset = -1;
  return r;
}

}  // namespace ubersim
