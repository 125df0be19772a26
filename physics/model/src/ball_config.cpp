#include "ubersim/physics/ball_config.hpp"

#include "ubersim/config_paths.hpp"

namespace ubersim::physics {

BallConfig load_ball_config(const ConfigFile& config, const std::string& name) {
  BallConfig b;
  b.name = name;
  b.radius = config.real_in("RADIUS", 0.005, 0.5);
  b.mass = config.real_in("MASS", 0.001, 10.0);
  b.sliding_deceleration = config.real_in("SLIDING_DECELERATION", 0.01, 50.0);
  b.rolling_deceleration = config.real_in("ROLLING_DECELERATION", 0.0, 50.0);
  if (b.rolling_deceleration >= b.sliding_deceleration) {
    config.fail("ROLLING_DECELERATION", "must be smaller than SLIDING_DECELERATION");
  }
  // A ball that starts without spin rolls at v0 / (1 + k) for I = k m r^2; a
  // ratio of 0.5 would need k = 1 (all mass beyond the surface).
  b.slide_to_roll_ratio = config.real_in("SLIDE_TO_ROLL_RATIO", 0.5, 0.99);
  b.bounce_restitution = config.real_in("BOUNCE_RESTITUTION", 0.0, 1.0);
  b.robot_restitution = config.real_in("ROBOT_RESTITUTION", 0.0, 1.0);
  config.require_all_used();
  return b;
}

BallConfig load_ball_config(const std::string& config_dir, const std::string& name) {
  const auto path = resolve_config(config_dir, "balls", name);
  return load_ball_config(ConfigFile::load(path), path.stem().string());
}

}  // namespace ubersim::physics
