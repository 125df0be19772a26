#include "ubersim/ssl_bridge/robot_specs_translation.hpp"

#include <ssl_simulation_custom_erforce_robot_spec.pb.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <ubersim/team_t.hpp>

#include "ubersim/ssl_bridge/units.hpp"

namespace ubersim::ssl {
namespace {

constexpr double kRadToDeg = 180.0 / kPi;

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", value);
  return text;
}

// One RobotSpecs being turned into config keys.
class SpecWriter {
 public:
  SpecWriter(const BaseRobotType& base, std::string field_prefix, Errors& errors)
      : base_(base), prefix_(std::move(field_prefix)), errors_(errors) {}

  // A positive, finite protocol value, else an error naming the field.
  bool usable(const char* field, double value) {
    if (std::isfinite(value) && value > 0) return true;
    add_error(errors_, kErrorInvalid,
              prefix_ + field + " must be finite and > 0 (got " + number(value) + "); not applied");
    return false;
  }
  void unsupported(const std::string& field, const std::string& why) {
    add_error(errors_, kErrorUnsupported, prefix_ + field + ": " + why);
  }
  void invalid(const std::string& field, const std::string& why) {
    add_error(errors_, kErrorInvalid, prefix_ + field + ": " + why);
  }
  void malformed(const std::string& field, const std::string& why) {
    add_error(errors_, kErrorMalformed, prefix_ + field + ": " + why);
  }
  void set(const std::string& key, double value) { overrides_[key] = {number(value)}; }
  void set(const std::string& key, std::vector<std::string> values) {
    overrides_[key] = std::move(values);
  }
  bool overridden(const std::string& key) const { return overrides_.count(key) != 0; }
  double value(const std::string& key, double base_value) const {
    const auto found = overrides_.find(key);
    return found == overrides_.end() ? base_value : std::stod(found->second.front());
  }

  std::string text() const {
    std::string out;
    const auto line = [&out](const std::string& key, const std::vector<std::string>& values) {
      out += key + " =";
      for (const std::string& v : values) out += " " + v;
      out += "\n";
    };
    std::map<std::string, std::vector<std::string>> pending = overrides_;
    for (const auto& [key, values] : base_.keys) {
      const auto found = pending.find(key);
      if (found == pending.end()) {
        line(key, values);
      } else {
        line(key, found->second);
        pending.erase(found);
      }
    }
    for (const auto& [key, values] : pending) line(key, values);  // optional keys the base left out
    return out;
  }

 private:
  const BaseRobotType& base_;
  std::string prefix_;
  Errors& errors_;
  std::map<std::string, std::vector<std::string>> overrides_;
};

void apply_limits(const RobotLimits& limits, SpecWriter& w) {
  if (limits.has_acc_speedup_absolute_max() &&
      w.usable("limits.acc_speedup_absolute_max", limits.acc_speedup_absolute_max())) {
    w.set("MAX_ACCELERATION", limits.acc_speedup_absolute_max());
  }
  if (limits.has_acc_speedup_angular_max() &&
      w.usable("limits.acc_speedup_angular_max", limits.acc_speedup_angular_max())) {
    w.set("MAX_ANGULAR_ACCELERATION", limits.acc_speedup_angular_max());
  }
  // Physics bounds braking (the part of a change that reduces the speed) on
  // its own; unset, a robot type brakes with its speed-up limit.
  if (limits.has_acc_brake_absolute_max() &&
      w.usable("limits.acc_brake_absolute_max", limits.acc_brake_absolute_max())) {
    w.set("MAX_BRAKE_ACCELERATION", limits.acc_brake_absolute_max());
  }
  if (limits.has_acc_brake_angular_max() &&
      w.usable("limits.acc_brake_angular_max", limits.acc_brake_angular_max())) {
    w.set("MAX_ANGULAR_BRAKE_ACCELERATION", limits.acc_brake_angular_max());
  }
  if (limits.has_vel_absolute_max() &&
      w.usable("limits.vel_absolute_max", limits.vel_absolute_max())) {
    w.set("MAX_SPEED", limits.vel_absolute_max());
  }
  if (limits.has_vel_angular_max() &&
      w.usable("limits.vel_angular_max", limits.vel_angular_max())) {
    w.set("MAX_ANGULAR_SPEED", limits.vel_angular_max());
  }
}

// The protocol's angles run clockwise from forward; ours counter-clockwise.
void apply_wheel_angles(const RobotWheelAngles& angles, const RobotTypeConfig& base,
                        SpecWriter& w) {
  if (base.drive != DriveKind::Omni || base.wheel_count() != 4) {
    w.unsupported("wheel_angles", "the base robot type " + base.name +
                                      " does not have four omni wheels; not applied");
    return;
  }
  const float values[] = {angles.front_right(), angles.back_right(), angles.back_left(),
                          angles.front_left()};
  for (float v : values) {
    if (!std::isfinite(v)) {
      w.invalid("wheel_angles", "every angle must be finite; not applied");
      return;
    }
  }
  const auto ccw_deg = [](float clockwise) {
    return number(std::fmod(360.0 - clockwise * kRadToDeg + 720.0, 360.0));
  };
  w.set("WHEEL_ANGLES_DEG", {ccw_deg(angles.front_left()), ccw_deg(angles.back_left()),
                             ccw_deg(angles.back_right()), ccw_deg(angles.front_right())});
}

// ER-Force's robot body (its simulator's simrobot.cpp and mesh.cpp): the hull
// is cut flat at center_to_dribbler; below a box 0.06 m above the floor (its
// dribbler bar's 0.04 m plus 0.02 m) the front is open, and the ball rests
// against the dribbler bar, whose face is at shoot_radius from the centre
// (the protocol: "from the robot center to the ball, when the ball is as close
// as possible"). In ubersim terms: FRONT_DISTANCE = center_to_dribbler,
// KICKER_DISTANCE = shoot_radius (where the kicker and dribbler meet the
// ball), and the mouth between them MOUTH_HEIGHT high.
constexpr double kErForceMouthHeight = 0.06;  // m, floor to the top of the opening

void apply_shoot_radius(double shoot_radius, const BaseRobotType& base, SpecWriter& w) {
  const RobotTypeConfig& b = base.config;
  const double front = w.value("FRONT_DISTANCE", b.front_distance);
  // A dribbler reaching out beyond the hull is not part of our body model:
  // the ball then rests on the flat front.
  const double kicker = std::min(static_cast<double>(shoot_radius), front);
  w.set("KICKER_DISTANCE", kicker);
  if (kicker < front) {
    // High enough for the ball, never above the robot.
    const double height = w.value("HEIGHT", b.height);
    const double clearance = w.value("GROUND_CLEARANCE", b.ground_clearance);
    const double mouth = std::max(kErForceMouthHeight, clearance + 2.5 * base.ball_radius);
    w.set("MOUTH_HEIGHT", std::min(mouth, height));
  }
}

void apply_custom(const google::protobuf::Any& any, const BaseRobotType& base, SpecWriter& w,
                  std::size_t index) {
  const std::string& url = any.type_url();
  const std::string type = url.substr(url.find_last_of('/') + 1);
  const std::string field = "custom[" + std::to_string(index) + "]";
  if (type != "RobotSpecErForce" && type != "sslsim.RobotSpecErForce") {
    w.unsupported(field, "type '" + type + "' is not known to ubersim (RobotSpecErForce is)");
    return;
  }
  RobotSpecErForce erforce;
  if (!erforce.ParseFromString(any.value())) {
    w.malformed(field, "does not decode as RobotSpecErForce; not applied");
    return;
  }
  if (erforce.has_shoot_radius() &&
      w.usable((field + ".shoot_radius").c_str(), erforce.shoot_radius())) {
    apply_shoot_radius(erforce.shoot_radius(), base, w);
  }
  if (erforce.has_dribbler_width() &&
      w.usable((field + ".dribbler_width").c_str(), erforce.dribbler_width())) {
    w.set("DRIBBLER_WIDTH", erforce.dribbler_width());
    w.set("KICKER_WIDTH", erforce.dribbler_width());
  }
}

// A base type with a mouth of its own keeps it only where the specs' body
// still has room for it.
void keep_mouth_inside(const RobotTypeConfig& b, SpecWriter& w) {
  const double front = w.value("FRONT_DISTANCE", b.front_distance);
  if (w.value("KICKER_DISTANCE", b.kicker_distance) > front) w.set("KICKER_DISTANCE", front);
  const double height = w.value("HEIGHT", b.height);
  if (b.mouth_height > 0 && w.value("MOUTH_HEIGHT", b.mouth_height) > height) {
    w.set("MOUTH_HEIGHT", height);
  }
}

}  // namespace

BaseRobotType base_robot_type(const ConfigFile& file, const RobotTypeConfig& config,
                              double ball_radius) {
  BaseRobotType base;
  for (const std::string& key : file.keys()) {
    if (key == "BASE") continue;
    base.keys.emplace_back(key, file.strings(key));
  }
  base.config = config;
  base.ball_radius = ball_radius;
  return base;
}

RobotSpecsTranslation translate_robot_specs(
    const google::protobuf::RepeatedPtrField<RobotSpecs>& all_specs, const BaseRobotType& base) {
  RobotSpecsTranslation out;
  const RobotTypeConfig& b = base.config;
  for (int i = 0; i < all_specs.size(); ++i) {
    const RobotSpecs& specs = all_specs[i];
    const std::string prefix = "robot_specs[" + std::to_string(i) + "].";
    if (specs.id().team() != YELLOW && specs.id().team() != BLUE) {
      add_error(out.errors, kErrorInvalid, prefix + "id.team must be YELLOW or BLUE; not applied");
      continue;
    }
    SpecWriter w(base, prefix, out.errors);
    DefinedRobotType type;
    type.team = specs.id().team() == YELLOW ? int8_t{team_t::YELLOW} : int8_t{team_t::BLUE};
    const std::string team = specs.id().team() == YELLOW ? "yellow" : "blue";
    type.name = "ssl_specs_" + team;
    if (specs.id().has_id()) {
      type.robot_id = static_cast<int32_t>(specs.id().id());
      type.name += "_" + std::to_string(specs.id().id());
    }
    // radius and height have protocol defaults (0.09, 0.15): applied also when unset.
    double radius = b.radius;
    if (w.usable("radius", specs.radius())) radius = specs.radius();
    w.set("RADIUS", radius);
    const double scale = radius / b.radius;  // the wheels move with the body's size
    w.set("WHEEL_DISTANCE", b.wheels.empty() ? 0.0 : b.wheels.front().distance * scale);
    if (w.usable("height", specs.height())) {
      w.set("HEIGHT", specs.height());
      w.set("CENTER_OF_MASS_HEIGHT",
            std::min(b.center_of_mass_height, 0.5 * static_cast<double>(specs.height())));
    }
    double mass = b.mass;
    if (specs.has_mass() && w.usable("mass", specs.mass())) {
      mass = specs.mass();
      w.set("MASS", mass);
    }
    // A solid of the same shape: inertia goes with mass and radius squared.
    w.set("MOMENT_OF_INERTIA", b.moment_of_inertia * (mass / b.mass) * scale * scale);
    if (specs.has_max_linear_kick_speed() &&
        w.usable("max_linear_kick_speed", specs.max_linear_kick_speed())) {
      w.set("KICK_MAX_SPEED", specs.max_linear_kick_speed());
    }
    if (specs.has_max_chip_kick_speed() &&
        w.usable("max_chip_kick_speed", specs.max_chip_kick_speed())) {
      w.set("CHIP_MAX_SPEED", specs.max_chip_kick_speed());
    }
    const bool has_front = specs.has_center_to_dribbler() &&
                           w.usable("center_to_dribbler", specs.center_to_dribbler());
    if (has_front) {
      w.set("FRONT_DISTANCE", specs.center_to_dribbler());
    } else if (b.front_distance > 0.9 * radius) {
      w.set("FRONT_DISTANCE", b.front_distance * scale);  // keep the front inside a smaller body
    }
    if (specs.has_limits()) apply_limits(specs.limits(), w);
    if (specs.has_wheel_angles()) apply_wheel_angles(specs.wheel_angles(), b, w);
    for (int c = 0; c < specs.custom_size(); ++c) {
      apply_custom(specs.custom(c), base, w, static_cast<std::size_t>(c));
    }
    keep_mouth_inside(b, w);
    type.radius = radius;
    type.config_text = w.text();
    out.types.push_back(std::move(type));
  }
  return out;
}

}  // namespace ubersim::ssl
