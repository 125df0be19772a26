#include "ubersim/referee/robot_radii.hpp"

#include <exception>
#include <utility>

#include "ubersim/robot_config.hpp"
#include "ubersim/robot_type_definition.hpp"

namespace ubersim::referee {

RobotRadii::RobotRadii(std::filesystem::path config_dir) : config_dir_(std::move(config_dir)) {}

double RobotRadii::fallback(const std::string& key, const std::string& why) {
  ++fallbacks_;
  log_.warn(key, why + "; assuming radius " + std::to_string(kFallbackRadius) + " m");
  return kFallbackRadius;
}

double RobotRadii::operator()(const std::string& type) {
  if (const auto found = radii_.find(type); found != radii_.end()) return found->second;
  // Never quoted: the bytes may be anything, of any length.
  if (!valid_robot_type_name(type)) {
    return fallback("type_name", "a robot type that is not a robot type name");
  }
  if (radii_.size() >= kMaxTypes) {
    return fallback("type_many", "robot type '" + type + "' is one more than the " +
                                     std::to_string(kMaxTypes) + " types looked up");
  }
  double radius = kFallbackRadius;
  try {
    radius = load_robot_config(config_dir_.string(), type).radius;
  } catch (const std::exception& error) {  // ConfigError, or the file system's
    radius = fallback("type_" + type, std::string("robot type '") + type + "': " + error.what());
  }
  return radii_[type] = radius;
}

}  // namespace ubersim::referee
