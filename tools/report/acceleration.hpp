#pragma once
// The paper's acceleration test (its Figure 7), for any robot type, driven the
// way a control program drives a robot: radio_packet_t on RADIO_YELLOW through
// the radio emulator, the trajectory read back from VISION and, beside it,
// from ground truth (SIM_STATE).
//
//  * Ramp: forward velocity commands that rise at 2 m/s^2, sent at the radio's
//    60 Hz, held on past the top speed; several trials, each with its own
//    vision and radio seeds. The acceleration is fitted where the ramp is
//    below the predicted top speed (10 % to 90 % of it), from ground truth
//    (slope of the speed) and from VISION (curvature of the position); the
//    speed where the robot stops following the ramp is its top speed.
//  * Sweep: the same ramp at steeper and steeper rates, to find where the
//    motors' torque or the wheels' traction stops the robot from following.
//    Sent as wheel speeds (the radio's MODE_WHEEL_SPEEDS, worked out from the
//    robot's wheel geometry as a team's software would) so that only physics
//    limits it; and, for comparison, as velocity commands, which the robot's
//    on-board acceleration limit (MAX_ACCELERATION) caps first.
#include <cstdint>
#include <string>
#include <vector>

#include "experiment_setup.hpp"
#include "predictions.hpp"

namespace ubersim::report {

struct TrajectorySample {
  double t = 0;  // s since the first command was sent
  double s = 0;  // m along the robot's starting heading, from where it started
  double v = 0;  // m/s along it (VISION: central difference of positions)
};

struct RampSettings {
  std::string robot_type;
  double acceleration = 2.0;  // m/s^2, commanded
  int trials = 5;
  std::uint64_t first_seed = 1;  // trial k uses vision and radio seed first_seed + k
  std::string vision_profile = "cmdragons02";
  std::string radio_profile = "cmdragons02";
  double hold = 0.6;  // s of commands after the ramp passes the predicted top speed
};

struct RampTrial {
  std::uint64_t seed = 0;
  std::vector<TrajectorySample> truth;   // every physics step
  std::vector<TrajectorySample> vision;  // every frame that saw the robot
  double truth_acceleration = 0;         // m/s^2, fitted in the window
  double vision_acceleration = 0;        // m/s^2 (NaN: too few frames in the window)
  double vision_standard_error = 0;      // m/s^2, of the fit
  double top_speed = 0;                  // m/s, mean ground-truth speed over the last 0.2 s
  double sideways_drift = 0;             // m, largest distance off the starting line
};

struct RampResult {
  RampSettings settings;
  DrivePrediction prediction;
  double command_delay = 0;  // s: radio latency + one step, where the ideal curve starts
  double window_begin = 0;   // s since the first command: the fit window
  double window_end = 0;
  std::vector<RampTrial> trials;
};

RampResult run_ramp(const ExperimentSetup& setup, const RampSettings& settings);

// Ideal constant-acceleration curve of a ramp, saturating at the predicted top speed.
TrajectorySample ideal_ramp(const RampResult& ramp, double t);

struct SweepSettings {
  std::string robot_type;
  // Commanded rates as fractions of the predicted physical limit.
  std::vector<double> fractions = {0.3, 0.5, 0.7, 0.85, 1.15, 1.4, 1.8};
  bool velocity_commands_too = true;  // also the same rates as velocity commands
  std::string vision_profile = "cmdragons02";
  std::string radio_profile = "cmdragons02";
  std::uint64_t seed = 11;
};

struct SweepPoint {
  bool wheel_speeds = true;          // false: velocity commands (on-board limit applies)
  double commanded = 0;              // m/s^2
  double truth = 0;                  // m/s^2, achieved, ground truth
  double vision = 0;                 // m/s^2, achieved, from VISION (NaN: too few frames)
  double vision_standard_error = 0;  // m/s^2, of that fit (few frames: large)
  bool reached_window = true;        // false: the robot never got through the speed window
};

struct SweepResult {
  SweepSettings settings;
  DrivePrediction prediction;
  std::vector<SweepPoint> points;
  double speed_window_low = 0, speed_window_high = 0;  // m/s: where accelerations are fitted
  // Mean achieved (ground truth, wheel-speed commands) over the rates at or
  // above 1.3 x the prediction: the measured saturation.
  double saturation = 0;
};

SweepResult run_sweep(const ExperimentSetup& setup, const SweepSettings& settings);

}  // namespace ubersim::report
