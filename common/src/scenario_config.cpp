#include "ubersim/scenario_config.hpp"

#include <algorithm>
#include <cmath>
#include <regex>

#include "ubersim/angles.hpp"
#include "ubersim/config_paths.hpp"

namespace ubersim {

ScenarioConfig load_scenario_config(const ConfigFile& config, const std::string& name) {
  ScenarioConfig s;
  s.name = name;
  s.field = config.string("FIELD");
  s.ball = config.string("BALL");
  const auto ball = config.reals("BALL_POSITION", 2);
  s.ball_x = ball[0];
  s.ball_y = ball[1];

  static const std::regex robot_key("(YELLOW|BLUE)_([0-9]{1,2})");
  for (const std::string& key : config.keys()) {
    std::smatch match;
    if (!std::regex_match(key, match, robot_key)) continue;
    const auto values = config.strings(key);
    if (values.size() != 4) {
      config.fail(key, "expected 4 values: robot type, x (m), y (m), heading (deg); got " +
                           std::to_string(values.size()));
    }
    RobotPlacement robot;
    robot.team = match[1] == "YELLOW" ? Team::Yellow : Team::Blue;
    robot.id = std::stoi(match[2]);
    robot.type = values[0];
    double numbers[3];
    for (int i = 0; i < 3; ++i) {
      try {
        std::size_t used = 0;
        numbers[i] = std::stod(values[static_cast<std::size_t>(i) + 1], &used);
        if (used != values[static_cast<std::size_t>(i) + 1].size() || !std::isfinite(numbers[i])) {
          throw std::invalid_argument("trailing");
        }
      } catch (const std::exception&) {
        config.fail(key, "expected a real number for " +
                             std::string(i == 0   ? "x"
                                         : i == 1 ? "y"
                                                  : "heading") +
                             ", got '" + values[static_cast<std::size_t>(i) + 1] + "'");
      }
    }
    robot.x = numbers[0];
    robot.y = numbers[1];
    robot.orientation = numbers[2] * kDegToRad;
    s.robots.push_back(robot);
  }
  std::sort(s.robots.begin(), s.robots.end(), [](const RobotPlacement& a, const RobotPlacement& b) {
    return std::make_pair(static_cast<int>(a.team), a.id) <
           std::make_pair(static_cast<int>(b.team), b.id);
  });
  config.require_all_used();
  return s;
}

ScenarioConfig load_scenario_config(const std::string& config_dir, const std::string& name) {
  const auto path = resolve_config(config_dir, "scenarios", name);
  return load_scenario_config(ConfigFile::load(path), path.stem().string());
}

}  // namespace ubersim
