#pragma once
// What the config files predict, worked out from the robot, ball and physics
// configs alone (never from the simulation): the numbers every measurement in
// the report is held against.
#include <string>

#include "ubersim/physics/ball_config.hpp"
#include "ubersim/robot_config.hpp"

namespace ubersim::report {

// Straight-line driving along the robot's forward axis (+x of the robot).
//
// Wheel i drives along the unit vector d_i and its axle lies along a_i (d_i
// turned by 90 deg); c_i = |d_i . x| is how much of its force pushes forward,
// s_i = |a_i . x| = sqrt(1 - c_i^2) how fast its contact slides across it.
// Every support (wheel or caster) carries the same static share of the weight,
// N = m g / (wheels + casters) (the load split physics uses: with casters the
// rigid chassis is statically indeterminate). Moving forward, every wheel's
// contact slides across its rollers (or tyre), which drags with the lateral
// friction mu_lat N s_i. So, with all wheels pushing as hard as they can:
//   traction-limited:  a = (sum_i c_i mu N - sum_i s_i mu_lat N) / m
//   torque-limited:    a = (sum_i c_i T / r - sum_i s_i mu_lat N) / (m + sum_i c_i^2 I_w / r^2)
// with I_w = m_w r^2 / 2 the spin inertia of a jointed-model wheel (a solid
// disc; 0 for the planar model, which has no wheel bodies). The robot gets the
// smaller. Its top speed is MAX_SPEED, or lower when the fastest-turning wheel
// reaches MOTOR_MAX_SPEED first: v = MOTOR_MAX_SPEED r / max_i c_i.
struct DrivePrediction {
  double torque_limited = 0;         // m/s^2
  double traction_limited = 0;       // m/s^2
  double acceleration = 0;           // m/s^2, the smaller of the two
  std::string limited_by;            // "motor torque" or "wheel traction"
  double roller_drag = 0;            // m/s^2, the lateral-friction drag included above
  double onboard_limit = 0;          // m/s^2, MAX_ACCELERATION (0 = none): velocity commands only
  double top_speed = 0;              // m/s
  std::string top_speed_limited_by;  // "MAX_SPEED" or "motor speed"
  double motor_top_speed = 0;        // m/s, MOTOR_MAX_SPEED r / max_i c_i
};
DrivePrediction predict_forward_drive(const RobotTypeConfig& robot, double gravity);

// A ball kicked flat (no spin) at v0: it slides at the sliding deceleration
// until its speed has fallen to SLIDE_TO_ROLL_RATIO v0, then rolls at the
// rolling deceleration until it stops.
struct RollOut {
  double slide_time = 0;      // s
  double slide_distance = 0;  // m
  double roll_speed = 0;      // m/s, where sliding turns to rolling
  double time = 0;            // s, kick to rest
  double distance = 0;        // m, kick to rest
};
RollOut predict_roll_out(const physics::BallConfig& ball, double v0);
// Speed (m/s) and distance (m) t seconds after the kick.
double roll_out_speed(const physics::BallConfig& ball, double v0, double t);
double roll_out_distance(const physics::BallConfig& ball, double v0, double t);

// A chip at speed v and elevation angle theta, no air drag, landing at the
// height it started from.
struct ChipFlight {
  double distance = 0;     // m, horizontal, launch to first touchdown
  double peak_height = 0;  // m, above the launch height
  double flight_time = 0;  // s
};
ChipFlight predict_chip(double speed, double angle, double gravity);

}  // namespace ubersim::report
