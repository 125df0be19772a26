#include "ubersim/vision/robot_sizes.hpp"

#include <exception>

#include "ubersim/robot_config.hpp"
#include "ubersim/spdlog.hpp"

namespace ubersim::vision {

RobotSizes RobotSizes::from_config_dir(const std::string& config_dir) {
  return RobotSizes([config_dir](const std::string& type) {
    const RobotTypeConfig config = load_robot_config(config_dir, type);
    return RobotSize{config.radius, config.height, config.front_distance};
  });
}

const RobotSize& RobotSizes::get(const std::string& type) {
  if (const auto found = cache_.find(type); found != cache_.end()) return found->second;
  RobotSize size;
  try {
    size = loader_(type);
  } catch (const std::exception& error) {
    spdlog::warn("robot type '{}': {}; assuming an SSL robot of radius {} m, height {} m", type,
                 error.what(), size.radius, size.height);
  }
  return cache_.emplace(type, size).first->second;
}

}  // namespace ubersim::vision
