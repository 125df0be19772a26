#pragma once
// The ball against its config: flat kicks (roll-out distance and time against
// the sliding/rolling model) and chip kicks (flight distance and peak height
// against the ballistic values). The kicks are a robot's kicker fired through
// the radio, as a control program fires it; the ball is measured in ground
// truth on a carpet long enough that even a 6.5 m/s kick stops before a wall.
#include <cstdint>
#include <string>
#include <vector>

#include "experiment_setup.hpp"
#include "predictions.hpp"

namespace ubersim::report {

struct BallSettings {
  std::string robot_type = "omni4_ssl";  // needs a kicker that reaches the speeds (and chips)
  std::vector<double> kick_speeds = {1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 6.5};  // m/s
  std::vector<double> chip_speeds = {2.0, 3.0, 4.0, 5.0};                 // m/s
  double chip_angle = 0.25 * M_PI;                                        // rad
  std::string vision_profile = "cmdragons02";
  std::string radio_profile = "cmdragons02";
  std::uint64_t seed = 5;
};

struct RollSample {
  double t = 0;  // s since the kick
  double s = 0;  // m travelled
  double v = 0;  // m/s
};

struct KickResult {
  double commanded = 0;             // m/s
  double launch_speed = 0;          // m/s, ball speed in the first state after the kick
  double distance = 0;              // m, kick to rest
  double time = 0;                  // s, kick to rest (speed below 5 mm/s)
  RollOut model;                    // from the commanded speed
  double sliding_deceleration = 0;  // m/s^2, fitted over the middle of the sliding phase
  double rolling_deceleration = 0;  // m/s^2, fitted over the middle of the rolling phase
  std::vector<RollSample> trajectory;
};

struct ChipSample {
  double t = 0;  // s since the kick
  double d = 0;  // m, horizontal distance from the launch point
  double z = 0;  // m, height of the ball's bottom above the carpet
};

struct ChipResult {
  double commanded = 0;  // m/s
  double angle = 0;      // rad
  double distance = 0;   // m, launch to first touchdown
  double peak = 0;       // m, highest point of the first flight (ball centre over its start)
  ChipFlight model;
  std::vector<ChipSample> trajectory;
};

struct BallResult {
  BallSettings settings;
  physics::BallConfig ball_config;  // the model's parameters
  double gravity = 0;               // m/s^2
  std::vector<KickResult> kicks;
  std::vector<ChipResult> chips;
};

BallResult run_ball(const ExperimentSetup& setup, const BallSettings& settings);

}  // namespace ubersim::report
