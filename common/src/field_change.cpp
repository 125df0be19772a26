#include "ubersim/field_change.hpp"

#include <cstdio>
#include <map>
#include <vector>

#include "ubersim/config.hpp"
#include "ubersim/robot_type_definition.hpp"

namespace ubersim {
namespace {

constexpr const char* kName = "field change";

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", value);
  return text;
}

std::map<std::string, std::string> keys_of(const FieldConfig& f) {
  return {{"FIELD_LENGTH", number(f.field_length)},
          {"FIELD_WIDTH", number(f.field_width)},
          {"BOUNDARY_WIDTH", number(f.boundary_width)},
          {"BOUNDARY_WIDTH_GOAL_LINE", number(f.boundary_width_goal_line)},
          {"GOAL_SUBSTITUTION_AREA_WIDTH", number(f.goal_substitution_area_width)},
          {"LINE_WIDTH", number(f.line_width)},
          {"GOAL_WIDTH", number(f.goal_width)},
          {"GOAL_DEPTH", number(f.goal_depth)},
          {"GOAL_HEIGHT", number(f.goal_height)},
          {"GOAL_WALL_THICKNESS", number(f.goal_wall_thickness)},
          {"WALL_HEIGHT", number(f.wall_height)},
          {"WALL_THICKNESS", number(f.wall_thickness)},
          {"CENTER_CIRCLE_RADIUS", number(f.center_circle_radius)},
          {"PENALTY_AREA_DEPTH", number(f.penalty_area_depth)},
          {"PENALTY_AREA_WIDTH", number(f.penalty_area_width)},
          {"PENALTY_MARK_DISTANCE", number(f.penalty_mark_distance)},
          {"WALL_RESTITUTION", number(f.wall_restitution)},
          {"WALL_FRICTION", number(f.wall_friction)}};
}

FieldChange apply_change(const FieldConfig& current, const std::string& text, bool ball_allowed) {
  if (text.size() > kMaxFieldChangeText) throw ConfigError(kName, 0, "longer than 4 KiB");
  if (names_a_base_file(text))
    throw ConfigError(kName, 0, "a field change cannot name a BASE file");
  const ConfigFile change = ConfigFile::parse(text, kName);
  FieldChange out;
  std::map<std::string, std::string> keys = keys_of(current);
  for (const std::string& key : change.keys()) {
    if (ball_allowed && key == kBallRadiusKey) {
      out.ball_radius = change.real_in(key, kMinBallRadius, kMaxBallRadius);
      continue;
    }
    if (keys.count(key) == 0) change.fail(key, "not a field key");
    const std::vector<std::string> values = change.strings(key, 1);
    keys[key] = values.front();
  }
  std::string merged;
  for (const auto& [key, value] : keys) merged += key + " = " + value + "\n";
  out.field = load_field_config(ConfigFile::parse(merged, kName), current.name);
  out.field.name = current.name;
  return out;
}

}  // namespace

FieldConfig change_field(const FieldConfig& current, const std::string& text) {
  return apply_change(current, text, false).field;
}

FieldChange change_field_and_ball(const FieldConfig& current, const std::string& text) {
  return apply_change(current, text, true);
}

}  // namespace ubersim
