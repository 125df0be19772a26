#include "ubersim/ssl_bridge/geometry_change_translation.hpp"

#include <cmath>
#include <cstdio>

#include "ubersim/ssl_bridge/calibration_translation.hpp"
#include "ubersim/ssl_bridge/units.hpp"

namespace ubersim::ssl {
namespace {

std::string line(const char* key, double metres) {
  char text[64];
  std::snprintf(text, sizeof text, "%s = %.6g\n", key, metres);
  return text;
}

}  // namespace

GeometryChange translate_geometry(const SSL_GeometryData& geometry,
                                  const field_geometry_t* current) {
  GeometryChange out;
  const SSL_GeometryFieldSize& f = geometry.field();
  std::string text;
  // Required fields: always there in a packet that decoded.
  text += line("FIELD_LENGTH", mm_to_m(f.field_length()));
  text += line("FIELD_WIDTH", mm_to_m(f.field_width()));
  text += line("GOAL_WIDTH", mm_to_m(f.goal_width()));
  text += line("GOAL_DEPTH", mm_to_m(f.goal_depth()));
  text += line("BOUNDARY_WIDTH", mm_to_m(f.boundary_width()));
  if (f.has_penalty_area_depth())
    text += line("PENALTY_AREA_DEPTH", mm_to_m(f.penalty_area_depth()));
  if (f.has_penalty_area_width())
    text += line("PENALTY_AREA_WIDTH", mm_to_m(f.penalty_area_width()));
  if (f.has_center_circle_radius()) {
    text += line("CENTER_CIRCLE_RADIUS", mm_to_m(f.center_circle_radius()));
  }
  if (f.has_line_thickness()) text += line("LINE_WIDTH", mm_to_m(f.line_thickness()));
  if (f.has_goal_center_to_penalty_mark()) {
    text += line("PENALTY_MARK_DISTANCE", mm_to_m(f.goal_center_to_penalty_mark()));
  }
  if (f.has_goal_height()) text += line("GOAL_HEIGHT", mm_to_m(f.goal_height()));
  out.field_config = text;

  if (f.has_boundary_width_goal_line() && f.boundary_width_goal_line() != f.boundary_width()) {
    add_error(out.errors, kErrorUnsupported,
              "geometry.field.boundary_width_goal_line: ubersim's walls stand at one margin all "
              "round (boundary_width); not applied");
  }
  if (f.has_ball_radius() && current != nullptr &&
      std::fabs(mm_to_m(f.ball_radius()) - current->ball_radius) > 0.0005) {
    add_error(out.errors, kErrorUnsupported,
              "geometry.field.ball_radius: the ball is the scenario's ball config; not applied");
  }
  CalibrationTranslation calibrations = translate_calibrations(geometry);
  out.cameras = calibrations.cameras;
  out.errors.insert(out.errors.end(), calibrations.errors.begin(), calibrations.errors.end());
  return out;
}

}  // namespace ubersim::ssl
