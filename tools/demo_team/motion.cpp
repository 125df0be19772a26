#include "motion.hpp"

#include <algorithm>
#include <cmath>

#include "ubersim/angles.hpp"

namespace demo {

ubersim::robot_command_t local_command(int robot_id, const Pose& pose, double vx, double vy,
                                       double omega) {
  ubersim::robot_command_t command{};
  command.robot_id = robot_id;
  command.mode = ubersim::robot_command_t::MODE_LOCAL_VELOCITY;
  const double c = std::cos(pose.orientation), s = std::sin(pose.orientation);
  command.vx = c * vx + s * vy;  // field frame -> robot frame
  command.vy = -s * vx + c * vy;
  command.omega = omega;
  return command;
}

namespace {

void limit(double& vx, double& vy, double max_speed) {
  const double speed = std::hypot(vx, vy);
  if (speed > max_speed) {
    vx *= max_speed / speed;
    vy *= max_speed / speed;
  }
}

double turn(const Pose& pose, double heading, const MotionLimits& limits) {
  const double error = ubersim::wrap_angle(heading - pose.orientation);
  return std::clamp(limits.heading_gain * error, -limits.max_angular_speed,
                    limits.max_angular_speed);
}

}  // namespace

ubersim::robot_command_t go_to(int robot_id, const Pose& pose, double x, double y, double heading,
                               const MotionLimits& limits) {
  double vx = limits.position_gain * (x - pose.x);
  double vy = limits.position_gain * (y - pose.y);
  limit(vx, vy, limits.max_speed);
  return local_command(robot_id, pose, vx, vy, turn(pose, heading, limits));
}

ubersim::robot_command_t track(int robot_id, const Pose& pose, double x_ref, double y_ref,
                               double vx_ref, double vy_ref, double heading,
                               const MotionLimits& limits) {
  double vx = vx_ref + limits.position_gain * (x_ref - pose.x);
  double vy = vy_ref + limits.position_gain * (y_ref - pose.y);
  limit(vx, vy, limits.max_speed);
  return local_command(robot_id, pose, vx, vy, turn(pose, heading, limits));
}

PathPoint figure_eight(double t, double centre_x, double centre_y, double size, double speed) {
  // Lemniscate of Gerono scaled to `size`: x = a sin(s), y = (a/2) sin(2s).
  // Its mean speed over a period is 0.970 a w; choose w for `speed`.
  const double a = size / 2;
  const double w = speed / (0.970 * a);
  const double s = w * t;
  return {centre_x + a * std::sin(s), centre_y + 0.5 * a * std::sin(2 * s), a * w * std::cos(s),
          a * w * std::cos(2 * s)};
}

}  // namespace demo
