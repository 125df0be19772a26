#pragma once
// SimulatorConfig.geometry.calib -> a camera set for the vision emulator
// (vision_cameras_t on VISION_CAMERAS), set up as the ER-Force simulator sets
// up its cameras from the same message: each camera hangs at its
// derived_camera_world_tx/ty/tz (mm), and which camera sees what follows
// from those positions (regions plus the realism camera_overlap, in the
// vision emulator). Focal length, principal point, distortion and image size
// are the camera's lens and image. The rotation q0..q3 (field -> camera,
// SSL-Vision's x, y, z, w) with tx, ty, tz is used where it is one: a unit
// quaternion looking down whose camera centre -R^T t is the derived
// position; otherwise the camera looks straight down (the official
// simulation geometry's q = 0.7, 0.7, 0.7, 0.7 is not a rotation, and the
// ER-Force simulator does not use q or t either).
#include <messages_robocup_ssl_geometry.pb.h>

#include <optional>
#include <ubersim/vision_cameras_t.hpp>

#include "ubersim/ssl_bridge/errors.hpp"

namespace ubersim::ssl {

struct CalibrationTranslation {
  std::optional<vision_cameras_t> cameras;  // request_id and sender left to the caller
  Errors errors;                            // an invalid calibration: no camera set at all
};

// Empty (no cameras, no errors) when the geometry has no calibration.
CalibrationTranslation translate_calibrations(const SSL_GeometryData& geometry);

}  // namespace ubersim::ssl
