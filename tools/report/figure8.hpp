#pragma once
// The paper's figure-8 (its Figure 8): a robot follows a figure-8 at about
// 0.8 m/s under the demo team's published controller (tools/demo_team:
// WorldModel fed from VISION, track() towards figure_eight(), one radio packet
// per camera frame, exactly as ubersim_demo_team --mode figure8 runs it). Run
// once with a latency/noise profile and once with an ideal one, the
// difference is what the emulation costs the controller.
#include <cstdint>
#include <string>
#include <vector>

#include "experiment_setup.hpp"
#include "fit.hpp"

namespace ubersim::report {

struct Figure8Settings {
  std::string label;  // names the run in the report
  std::string robot_type = "omni3_cmdragons02";
  std::string vision_profile = "cmdragons02";
  std::string radio_profile = "cmdragons02";
  std::uint64_t seed = 8;
  double speed = 0.8;  // m/s, mean speed along the path
  double size = 2.0;   // m across (the figure-8 is half as wide as it is long)
  double laps = 3;     // the first lap is left out of the errors (start from rest)
};

struct PathSample {
  double t = 0;  // s since the start
  double x = 0, y = 0;
};

struct Figure8Result {
  Figure8Settings settings;
  double period = 0;                  // s per lap
  std::vector<PathSample> truth;      // every physics step
  std::vector<PathSample> vision;     // every frame that saw the robot
  std::vector<PathSample> reference;  // where the path says the robot should be, every step
  std::vector<PathSample> path;       // the intended curve, one lap, finely sampled
  // Over laps 2.. (t >= one period):
  ErrorSummary tracking;        // m, ground truth to the reference point at the same time
  ErrorSummary contour;         // m, ground truth to the nearest point of the curve
  ErrorSummary vision_contour;  // m, VISION to the nearest point of the curve
  double mean_speed = 0;        // m/s, ground truth
  int packets = 0;              // radio packets the controller sent
};

Figure8Result run_figure8(const ExperimentSetup& setup, const Figure8Settings& settings);

}  // namespace ubersim::report
