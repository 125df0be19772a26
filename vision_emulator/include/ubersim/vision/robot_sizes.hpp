#pragma once
// The sizes of robot types, looked up by the robot_type name physics puts in
// each robot's state and read from config/robots/<name>.cfg once per name.
// The vision emulator needs a robot's height (its pattern is on top, and the
// vision system intersects camera rays with that height) and its outline (for
// hiding the ball).
#include <functional>
#include <string>
#include <unordered_map>

namespace ubersim::vision {

struct RobotSize {
  double radius = 0.09;           // m
  double height = 0.15;           // m
  double front_distance = 0.075;  // m, centre to the flat front
};

class RobotSizes {
 public:
  // Reads a robot type's size; throws (any exception) when the type is unknown.
  using Loader = std::function<RobotSize(const std::string& type)>;

  explicit RobotSizes(Loader loader) : loader_(std::move(loader)) {}
  // A loader reading <config_dir>/robots/<type>.cfg.
  static RobotSizes from_config_dir(const std::string& config_dir);

  // The size of a type; an unknown type gets the SSL maximum size (logged once).
  const RobotSize& get(const std::string& type);
  // A type defined at run time (SIM_CONTROL DEFINE_ROBOT_TYPE): replaces what
  // was known under that name. False (nothing kept) once kMaxTypes names are
  // known: the definitions come from the network.
  bool define(const std::string& type, const RobotSize& size) {
    if (cache_.count(type) == 0 && cache_.size() >= kMaxTypes) return false;
    cache_[type] = size;
    return true;
  }
  static constexpr std::size_t kMaxTypes = 256;

 private:
  Loader loader_;
  std::unordered_map<std::string, RobotSize> cache_;
};

}  // namespace ubersim::vision
