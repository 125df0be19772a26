#include "targets.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace ubersim::report {

bool Check::met() const {
  return std::isfinite(measured) && std::abs(error()) <= tolerance;
}

double Check::error() const {
  return (measured - expected) / expected;
}

std::vector<Check> check_ramp(const RampResult& ramp, const Tolerances& t) {
  std::vector<Check> checks;
  const std::string type = ramp.settings.robot_type;
  for (const auto& trial : ramp.trials) {
    const std::string name = type + " ramp (seed " + std::to_string(trial.seed) + ")";
    checks.push_back({name + ": acceleration, ground truth", trial.truth_acceleration,
                      ramp.settings.acceleration, t.acceleration});
    checks.push_back({name + ": acceleration, VISION", trial.vision_acceleration,
                      ramp.settings.acceleration, t.acceleration});
    checks.push_back(
        {name + ": top speed", trial.top_speed, ramp.prediction.top_speed, t.saturation});
  }
  return checks;
}

double expected_sweep_acceleration(const SweepResult& sweep, const SweepPoint& point) {
  double expected = std::min(point.commanded, sweep.prediction.acceleration);
  if (!point.wheel_speeds && sweep.prediction.onboard_limit > 0) {
    expected = std::min(expected, sweep.prediction.onboard_limit);
  }
  return expected;
}

std::vector<Check> check_sweep(const SweepResult& sweep, const Tolerances& t) {
  std::vector<Check> checks;
  const std::string type = sweep.settings.robot_type;
  for (const auto& point : sweep.points) {
    // Below the predicted saturation the robot must follow the command; at and
    // around the knee the achieved rate is between the two by nature.
    if (point.commanded >= sweep.prediction.acceleration) continue;
    const bool capped_onboard = !point.wheel_speeds && sweep.prediction.onboard_limit > 0 &&
                                point.commanded > sweep.prediction.onboard_limit;
    char rate[32];
    std::snprintf(rate, sizeof rate, "%.2f", point.commanded);
    checks.push_back({type + (point.wheel_speeds ? " wheel-speed" : " velocity") + " ramp at " +
                          rate + " m/s^2" + (capped_onboard ? " (on-board limit)" : "") +
                          (point.reached_window ? "" : " (never reached the speed window)"),
                      point.truth, expected_sweep_acceleration(sweep, point), t.acceleration});
  }
  checks.push_back({type + " saturation (wheel-speed commands)", sweep.saturation,
                    sweep.prediction.acceleration, t.saturation});
  return checks;
}

std::vector<Check> check_ball(const BallResult& ball, const Tolerances& t) {
  std::vector<Check> checks;
  char name[96];
  for (const auto& k : ball.kicks) {
    std::snprintf(name, sizeof name, "flat kick %.1f m/s: roll-out distance", k.commanded);
    checks.push_back({name, k.distance, k.model.distance, t.roll_out});
    std::snprintf(name, sizeof name, "flat kick %.1f m/s: roll-out time", k.commanded);
    checks.push_back({name, k.time, k.model.time, t.roll_out});
  }
  for (const auto& c : ball.chips) {
    std::snprintf(name, sizeof name, "chip %.1f m/s: flight distance", c.commanded);
    checks.push_back({name, c.distance, c.model.distance, t.chip});
    std::snprintf(name, sizeof name, "chip %.1f m/s: peak height", c.commanded);
    checks.push_back({name, c.peak, c.model.peak_height, t.chip});
  }
  return checks;
}

}  // namespace ubersim::report
