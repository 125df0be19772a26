#pragma once
// A scenario (config/scenarios/*.cfg): which field, which ball, where the ball
// starts, and which robots of which types stand where.
//
//   FIELD = division_b
//   BALL = ssl_golf_ball
//   BALL_POSITION = 0 0          # m
//   YELLOW_0 = omni4_ssl -4.0 0.0 0    # type, x (m), y (m), heading (deg)
//   BLUE_3 = omni4_ssl 1.0 -1.0 180
#include <string>
#include <vector>

#include "ubersim/channels.hpp"
#include "ubersim/config.hpp"

namespace ubersim {

struct RobotPlacement {
  Team team = Team::Yellow;
  int id = 0;
  std::string type;
  double x = 0;            // m
  double y = 0;            // m
  double orientation = 0;  // rad
};

struct ScenarioConfig {
  std::string name;
  std::string field;
  std::string ball;
  double ball_x = 0;                   // m
  double ball_y = 0;                   // m
  std::vector<RobotPlacement> robots;  // sorted by team, then id
};

ScenarioConfig load_scenario_config(const ConfigFile& config, const std::string& name);
ScenarioConfig load_scenario_config(const std::string& config_dir, const std::string& name);

}  // namespace ubersim
