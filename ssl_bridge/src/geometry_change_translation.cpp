#include "ubersim/ssl_bridge/geometry_change_translation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "ubersim/field_change.hpp"
#include "ubersim/ssl_bridge/calibration_translation.hpp"
#include "ubersim/ssl_bridge/units.hpp"

namespace ubersim::ssl {
namespace {

std::string line(const char* key, double metres) {
  char text[64];
  std::snprintf(text, sizeof text, "%s = %.6g\n", key, metres);
  return text;
}

// SSL-Vision's default width of the goal substitution area (both divisions).
constexpr double kDefaultGoalSubstitutionAreaWidth = 0.3;  // m

// The area behind the goal lines: field 16 when sent, else (as the protocol
// and the official game controller read it) the same as along the touch lines.
double boundary_width_goal_line(const SSL_GeometryFieldSize& f) {
  return mm_to_m(f.has_boundary_width_goal_line() ? f.boundary_width_goal_line()
                                                  : f.boundary_width());
}

// Field 17 when sent; else the width in use (or the default), cut to the new
// area behind the goal line so that a smaller field stays a legal config.
double goal_substitution_area_width(const SSL_GeometryFieldSize& f,
                                    const field_geometry_t* current) {
  if (f.has_goal_substitution_area_width()) return mm_to_m(f.goal_substitution_area_width());
  const double kept = current != nullptr ? current->goal_substitution_area_width
                                         : kDefaultGoalSubstitutionAreaWidth;
  return std::min(kept, boundary_width_goal_line(f));
}

// The ball in play takes the geometry's radius (physics rebuilds it and the
// robots around it); within half a millimetre of ours it stays as it is.
void add_ball_radius(float radius_mm, const field_geometry_t* current, std::string& text,
                     Errors& errors) {
  const double radius = mm_to_m(radius_mm);
  if (!std::isfinite(radius) || radius < kMinBallRadius || radius > kMaxBallRadius) {
    char what[96];
    std::snprintf(what, sizeof what, "geometry.field.ball_radius must be %g to %g mm; not applied",
                  m_to_mm(kMinBallRadius), m_to_mm(kMaxBallRadius));
    add_error(errors, kErrorInvalid, what);
    return;
  }
  constexpr double kSameBall = 0.0005;  // m
  if (current != nullptr && std::fabs(radius - current->ball_radius) <= kSameBall) return;
  text += line(kBallRadiusKey, radius);
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
  text += line("BOUNDARY_WIDTH_GOAL_LINE", boundary_width_goal_line(f));
  text += line("GOAL_SUBSTITUTION_AREA_WIDTH", goal_substitution_area_width(f, current));
  if (f.has_penalty_area_depth())
    text += line("PENALTY_AREA_DEPTH", mm_to_m(f.penalty_area_depth()));
  if (f.has_penalty_area_width())
    text += line("PENALTY_AREA_WIDTH", mm_to_m(f.penalty_area_width()));
  if (f.has_center_circle_radius()) {
    text += line("CENTER_CIRCLE_RADIUS", mm_to_m(f.center_circle_radius()));
  }
  if (f.has_line_thickness()) text += line("LINE_WIDTH", mm_to_m(f.line_thickness()));
  if (f.has_goal_center_to_penalty_mark()) {
    // Both measure from the centre of the goal attacked.
    text += line("PENALTY_MARK_DISTANCE", mm_to_m(f.goal_center_to_penalty_mark()));
  }
  if (f.has_goal_height()) text += line("GOAL_HEIGHT", mm_to_m(f.goal_height()));
  if (f.has_ball_radius()) add_ball_radius(f.ball_radius(), current, text, out.errors);
  out.field_config = text;

  CalibrationTranslation calibrations = translate_calibrations(geometry);
  out.cameras = calibrations.cameras;
  out.errors.insert(out.errors.end(), calibrations.errors.begin(), calibrations.errors.end());
  return out;
}

}  // namespace ubersim::ssl
