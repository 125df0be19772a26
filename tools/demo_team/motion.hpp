#pragma once
// Motion control a team would run on its computer: drive a robot to a pose or
// along a timed path, producing robot-relative velocity commands (what the
// robot's radio expects).
#include <ubersim/robot_command_t.hpp>

#include "world_model.hpp"

namespace demo {

struct MotionLimits {
  double max_speed = 2.0;          // m/s
  double max_angular_speed = 6.0;  // rad/s
  double position_gain = 3.0;      // 1/s
  double heading_gain = 4.0;       // 1/s
};

// Field-frame velocity (vx, vy, omega) turned into a robot-frame command.
ubersim::robot_command_t local_command(int robot_id, const Pose& pose, double vx, double vy,
                                       double omega);

// Proportional drive to (x, y, heading) with speed limits.
ubersim::robot_command_t go_to(int robot_id, const Pose& pose, double x, double y, double heading,
                               const MotionLimits& limits);

// Tracks a moving target with feed-forward of its velocity (vx_ref, vy_ref).
ubersim::robot_command_t track(int robot_id, const Pose& pose, double x_ref, double y_ref,
                               double vx_ref, double vy_ref, double heading,
                               const MotionLimits& limits);

// The paper's figure-8: two loops through `centre`, `size` m across, at about
// `speed` m/s. Returns position and velocity at time t (s).
struct PathPoint {
  double x, y, vx, vy;
};
PathPoint figure_eight(double t, double centre_x, double centre_y, double size, double speed);

}  // namespace demo
