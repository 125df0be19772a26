#include "ubersim/field_config.hpp"

#include <algorithm>
#include <filesystem>

#include "ubersim/config_paths.hpp"

namespace ubersim {

namespace {
constexpr double kDefaultGoalSubstitutionAreaWidth = 0.3;  // m, SSL rules (ssl-vision's default)
}  // namespace

FieldConfig load_field_config(const ConfigFile& config, const std::string& name) {
  constexpr double kMaxLength = 100.0;  // m: anything longer is a unit mistake
  FieldConfig f;
  f.name = name;
  f.field_length = config.real_in("FIELD_LENGTH", 0.5, kMaxLength);
  f.field_width = config.real_in("FIELD_WIDTH", 0.5, kMaxLength);
  f.boundary_width = config.real_in("BOUNDARY_WIDTH", 0.0, kMaxLength);
  // SSL's geometry (field 16) may leave more room behind the goal lines than
  // along the touch lines (2026 Division A: 0.6 m and 0.3 m).
  f.boundary_width_goal_line = config.has("BOUNDARY_WIDTH_GOAL_LINE")
                                   ? config.real_in("BOUNDARY_WIDTH_GOAL_LINE", 0.0, kMaxLength)
                                   : f.boundary_width;
  f.line_width = config.real_in("LINE_WIDTH", 0.0, 1.0);
  f.goal_width = config.real_in("GOAL_WIDTH", 0.05, f.field_width);
  f.goal_depth = config.real_in("GOAL_DEPTH", 0.01, kMaxLength);
  f.goal_height = config.real_in("GOAL_HEIGHT", 0.01, 10.0);
  f.goal_wall_thickness = config.real_in("GOAL_WALL_THICKNESS", 0.001, 1.0);
  f.wall_height = config.real_in("WALL_HEIGHT", 0.01, 10.0);
  f.wall_thickness = config.real_in("WALL_THICKNESS", 0.001, 1.0);
  f.center_circle_radius = config.real_in("CENTER_CIRCLE_RADIUS", 0.0, f.field_width / 2);
  f.penalty_area_depth = config.real_in("PENALTY_AREA_DEPTH", 0.0, f.field_length / 2);
  f.penalty_area_width = config.real_in("PENALTY_AREA_WIDTH", 0.0, f.field_width);
  // From the centre of the goal attacked, as the official programs measure it:
  // the Division A mark (8 m) lies in the attacker's own half.
  f.penalty_mark_distance = config.real_in("PENALTY_MARK_DISTANCE", 0.0, f.field_length);
  // The rules' 0.3 m, or all of the area behind the goal line if that is narrower.
  f.goal_substitution_area_width =
      config.has("GOAL_SUBSTITUTION_AREA_WIDTH")
          ? config.real_in("GOAL_SUBSTITUTION_AREA_WIDTH", 0.0, f.boundary_width_goal_line)
          : std::min(kDefaultGoalSubstitutionAreaWidth, f.boundary_width_goal_line);
  f.wall_restitution = config.real_in("WALL_RESTITUTION", 0.0, 1.0);
  f.wall_friction = config.real_in("WALL_FRICTION", 0.0, 10.0);
  if (f.goal_depth > f.boundary_width_goal_line + f.wall_thickness &&
      f.boundary_width_goal_line > 0) {
    // Goals stand in the boundary area; a deeper goal would poke through the wall.
    config.fail("GOAL_DEPTH",
                "goal is deeper than the boundary area behind the goal line plus "
                "wall (" +
                    std::to_string(f.boundary_width_goal_line + f.wall_thickness) + " m)");
  }
  config.require_all_used();
  return f;
}

FieldConfig load_field_config(const std::string& config_dir, const std::string& name) {
  const auto path = resolve_config(config_dir, "fields", name);
  return load_field_config(ConfigFile::load(path), path.stem().string());
}

field_geometry_t FieldConfig::to_message(double ball_radius) const {
  field_geometry_t m{};
  m.name = name;
  m.field_length = field_length;
  m.field_width = field_width;
  m.boundary_width = boundary_width;
  m.line_width = line_width;
  m.goal_width = goal_width;
  m.goal_depth = goal_depth;
  m.goal_height = goal_height;
  m.goal_wall_thickness = goal_wall_thickness;
  m.wall_height = wall_height;
  m.wall_thickness = wall_thickness;
  m.center_circle_radius = center_circle_radius;
  m.penalty_area_depth = penalty_area_depth;
  m.penalty_area_width = penalty_area_width;
  m.ball_radius = ball_radius;
  m.penalty_mark_distance = penalty_mark_distance;
  m.boundary_width_goal_line = boundary_width_goal_line;
  m.goal_substitution_area_width = goal_substitution_area_width;
  return m;
}

}  // namespace ubersim
