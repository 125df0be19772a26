#pragma once
// The tolerances the physics issue sets, and the checks of every experiment
// against them. The report prints them; the CTest fails on them. Nothing here
// is tuned to the measurements: a missed target is reported as missed.
#include <string>
#include <vector>

#include "acceleration.hpp"
#include "ball.hpp"
#include "figure8.hpp"

namespace ubersim::report {

struct Tolerances {
  double acceleration = 0.05;  // relative, below the predicted saturation
  double saturation = 0.10;    // relative, saturation (and top speed) against the prediction
  double roll_out = 0.10;      // relative, distance and time against the model
  double chip = 0.10;          // relative, flight distance and peak height against ballistics
};

struct Check {
  std::string what;  // e.g. "omni4_ssl ramp trial 3: acceleration (ground truth)"
  double measured = 0;
  double expected = 0;
  double tolerance = 0;  // relative
  bool met() const;
  double error() const;  // relative: (measured - expected) / expected
};

std::vector<Check> check_ramp(const RampResult& ramp, const Tolerances& t = {});
std::vector<Check> check_sweep(const SweepResult& sweep, const Tolerances& t = {});
std::vector<Check> check_ball(const BallResult& ball, const Tolerances& t = {});

// What a sweep point should reach: the commanded rate below the predicted
// saturation (and, for velocity commands, below the on-board limit).
double expected_sweep_acceleration(const SweepResult& sweep, const SweepPoint& point);

}  // namespace ubersim::report
