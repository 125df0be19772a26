#pragma once
// SimulatorConfig.geometry -> a SET_FIELD request: the field sizes (mm) become
// "KEY = value" lines (m) of a field config, which physics applies to the field
// in use. The lines and arcs follow from the sizes (ignored). A ball radius
// more than 0.5 mm from the ball in play becomes BALL_RADIUS (physics gives
// the ball that radius); the camera calibrations become the vision emulator's
// cameras (calibration_translation.hpp).
#include <messages_robocup_ssl_geometry.pb.h>

#include <optional>
#include <string>
#include <ubersim/field_geometry_t.hpp>
#include <ubersim/vision_cameras_t.hpp>

#include "ubersim/ssl_bridge/errors.hpp"

namespace ubersim::ssl {

struct GeometryChange {
  std::optional<std::string> field_config;  // for SIM_CONTROL SET_FIELD
  std::optional<vision_cameras_t> cameras;  // the calibrations, for VISION_CAMERAS
  Errors errors;
};

// `current`: the field ubersim reports now (null: none seen yet).
GeometryChange translate_geometry(const SSL_GeometryData& geometry,
                                  const field_geometry_t* current);

}  // namespace ubersim::ssl
