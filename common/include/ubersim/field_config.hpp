#pragma once
// A field config (config/fields/*.cfg) read into plain data.
#include <string>
#include <ubersim/field_geometry_t.hpp>

#include "ubersim/config.hpp"

namespace ubersim {

struct FieldConfig {
  std::string name;
  double field_length = 0;              // m
  double field_width = 0;               // m
  double boundary_width = 0;            // m, touch lines to the walls
  double boundary_width_goal_line = 0;  // m, goal lines to the walls
  double line_width = 0;                // m
  double goal_width = 0;                // m
  double goal_depth = 0;                // m
  double goal_height = 0;               // m
  double goal_wall_thickness = 0;       // m
  double wall_height = 0;               // m
  double wall_thickness = 0;            // m
  double center_circle_radius = 0;      // m
  double penalty_area_depth = 0;        // m
  double penalty_area_width = 0;        // m
  // m, from the centre of the goal attacked to the penalty mark (SSL's
  // goal_center_to_penalty_mark; the GC's PenaltyKickDistToGoal)
  double penalty_mark_distance = 0;
  // m, depth of the goal substitution area, from the wall behind each goal line
  double goal_substitution_area_width = 0;
  double wall_restitution = 0;  // unitless
  double wall_friction = 0;     // unitless

  // Inner faces of the boundary walls: |x| <= half_length_to_wall(), same for y.
  double half_length_to_wall() const { return field_length / 2 + boundary_width_goal_line; }
  double half_width_to_wall() const { return field_width / 2 + boundary_width; }

  field_geometry_t to_message(double ball_radius) const;
};

// Reads every key of a field file (and rejects any other). Throws ConfigError.
FieldConfig load_field_config(const ConfigFile& config, const std::string& name);
FieldConfig load_field_config(const std::string& config_dir, const std::string& name);

}  // namespace ubersim
