#include "predictions.hpp"

#include <algorithm>
#include <cmath>

namespace ubersim::report {

DrivePrediction predict_forward_drive(const RobotTypeConfig& robot, double gravity) {
  DrivePrediction p;
  const std::size_t casters = robot.caster_positions.size() / 2;  // x y pairs
  const auto supports = static_cast<double>(robot.wheels.size() + casters);
  const double load = robot.mass * gravity / supports;  // N per support
  const double r = robot.wheel_radius;
  const double spin_inertia =
      robot.model == DriveModel::Jointed ? robot.wheel_mass * r * r / 2 : 0.0;
  double push = 0, drag = 0, inertia = 0, fastest = 0;
  for (const auto& w : robot.wheels) {
    const double c = std::abs(w.drive_x);
    const double s = std::sqrt(std::max(0.0, 1 - c * c));
    push += c;
    drag += s * robot.wheel_lateral_friction * load;
    inertia += c * c * spin_inertia / (r * r);
    fastest = std::max(fastest, c);
  }
  p.roller_drag = drag / robot.mass;
  p.traction_limited = (push * robot.wheel_friction * load - drag) / robot.mass;
  p.torque_limited = (push * robot.motor_max_torque / r - drag) / (robot.mass + inertia);
  if (p.torque_limited < p.traction_limited) {
    p.acceleration = p.torque_limited;
    p.limited_by = "motor torque";
  } else {
    p.acceleration = p.traction_limited;
    p.limited_by = "wheel traction";
  }
  p.onboard_limit = robot.max_acceleration;
  p.motor_top_speed = fastest > 0 ? robot.motor_max_speed * r / fastest : 0;
  if (p.motor_top_speed < robot.max_speed) {
    p.top_speed = p.motor_top_speed;
    p.top_speed_limited_by = "motor speed";
  } else {
    p.top_speed = robot.max_speed;
    p.top_speed_limited_by = "MAX_SPEED";
  }
  return p;
}

RollOut predict_roll_out(const physics::BallConfig& ball, double v0) {
  RollOut r;
  r.roll_speed = ball.slide_to_roll_ratio * v0;
  r.slide_time = (v0 - r.roll_speed) / ball.sliding_deceleration;
  r.slide_distance = (v0 * v0 - r.roll_speed * r.roll_speed) / (2 * ball.sliding_deceleration);
  const double roll_time =
      ball.rolling_deceleration > 0 ? r.roll_speed / ball.rolling_deceleration : 0;
  r.time = r.slide_time + roll_time;
  r.distance = r.slide_distance + r.roll_speed * roll_time / 2;
  return r;
}

double roll_out_speed(const physics::BallConfig& ball, double v0, double t) {
  const RollOut r = predict_roll_out(ball, v0);
  if (t <= 0) return v0;
  if (t < r.slide_time) return v0 - ball.sliding_deceleration * t;
  return std::max(0.0, r.roll_speed - ball.rolling_deceleration * (t - r.slide_time));
}

double roll_out_distance(const physics::BallConfig& ball, double v0, double t) {
  const RollOut r = predict_roll_out(ball, v0);
  if (t <= 0) return 0;
  if (t < r.slide_time) return v0 * t - ball.sliding_deceleration * t * t / 2;
  const double rolling = std::min(t, r.time) - r.slide_time;
  return r.slide_distance + r.roll_speed * rolling -
         ball.rolling_deceleration * rolling * rolling / 2;
}

ChipFlight predict_chip(double speed, double angle, double gravity) {
  ChipFlight f;
  const double up = speed * std::sin(angle);
  const double along = speed * std::cos(angle);
  f.flight_time = 2 * up / gravity;
  f.distance = along * f.flight_time;
  f.peak_height = up * up / (2 * gravity);
  return f;
}

}  // namespace ubersim::report
