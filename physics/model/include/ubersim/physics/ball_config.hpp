#pragma once
// A ball (config/balls/*.cfg) read into plain data.
#include <string>

#include "ubersim/config.hpp"

namespace ubersim::physics {

struct BallConfig {
  std::string name;
  double radius = 0;                // m
  double mass = 0;                  // kg
  double sliding_deceleration = 0;  // m/s^2, while the ball slides on the carpet
  double rolling_deceleration = 0;  // m/s^2, once it rolls
  double slide_to_roll_ratio = 0;   // unitless: speed where sliding turns to rolling / start speed
  double bounce_restitution = 0;    // unitless, vertical speed kept per bounce on the carpet
  double robot_restitution = 0;     // unitless, against a robot's chassis
};

// Reads every key (and rejects any other). Throws ConfigError.
BallConfig load_ball_config(const ConfigFile& config, const std::string& name);
BallConfig load_ball_config(const std::string& config_dir, const std::string& name);

}  // namespace ubersim::physics
