#pragma once
// Between numpy and the simulation: the commands array in, ground truth,
// vision detections and radio feedback out (docs/python.md, "Arrays").
// Every column list is named once here; Python reads the names from the
// module (ubersim.COMMAND_COLUMNS, ...).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <array>
#include <vector>

#include "in_process_sim.hpp"

namespace ubersim::python {

namespace py = pybind11;

inline constexpr std::array<const char*, 14> kCommandColumns{
    "team",   "id",     "mode",   "vx",         "vy",         "omega",      "wheel0",
    "wheel1", "wheel2", "wheel3", "kick_speed", "chip_speed", "chip_angle", "dribbler_speed"};
inline constexpr std::array<const char*, 14> kRobotColumns{"team",
                                                           "id",
                                                           "x",
                                                           "y",
                                                           "orientation",
                                                           "vx",
                                                           "vy",
                                                           "omega",
                                                           "ball_contact",
                                                           "kicker_charged",
                                                           "wheel0",
                                                           "wheel1",
                                                           "wheel2",
                                                           "wheel3"};
inline constexpr std::array<const char*, 6> kBallColumns{"x", "y", "z", "vx", "vy", "vz"};
inline constexpr std::array<const char*, 10> kDetectionColumns{
    "camera_id", "frame_number", "t_capture", "t_sent", "kind",
    "robot_id",  "confidence",   "x",         "y",      "orientation"};
inline constexpr std::array<const char*, 7> kFrameColumns{
    "camera_id", "frame_number", "t_capture", "t_sent", "balls", "robots_yellow", "robots_blue"};
inline constexpr std::array<const char*, 6> kFeedbackColumns{
    "team", "robot_id", "t_measured", "t_sent", "ball_contact", "kicker_charged"};
inline constexpr int kMaxWheels = 4;

// Detection kinds (the "kind" column).
inline constexpr double kKindBall = 0, kKindYellow = 1, kKindBlue = 2;

template <std::size_t N>
py::tuple column_names(const std::array<const char*, N>& columns) {
  py::tuple names(N);
  for (std::size_t i = 0; i < N; ++i) names[i] = columns[i];
  return names;
}

// The commands array (n, 14) or None -> orders; raises ValueError naming the
// row and column of anything wrong. `label` prefixes messages ("world 3: ").
std::vector<RobotOrder> orders_from_array(const py::handle& commands, const InProcessSim& sim,
                                          const std::string& label);

// Ground truth as arrays: robots (n, 14) and ball (6,).
py::array_t<double> robots_array(const sim_state_t& state);
py::array_t<double> ball_array(const sim_state_t& state);
py::array_t<double> detections_array(const std::vector<vision_frame_t>& frames);
py::array_t<double> frames_array(const std::vector<vision_frame_t>& frames);
py::array_t<double> feedback_array(const std::vector<std::pair<Team, radio_feedback_t>>& feedback);

// {"time", "robots", "ball"}, and with a step's output also
// {"vision", "frames", "feedback"}.
py::dict truth_dict(const sim_state_t& state);
py::dict step_dict(const StepOutput& out);

}  // namespace ubersim::python
