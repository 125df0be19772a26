#pragma once
// What every experiment shares: where things are, the configs predictions are
// made from, the scenario files the experiments run in, and the samples they
// record from SIM_STATE (ground truth) and VISION (what a controller sees).
#include <string>
#include <ubersim/sim_state_t.hpp>
#include <ubersim/vision_frame_t.hpp>
#include <vector>

#include "sim_rig.hpp"
#include "ubersim/physics/ball_config.hpp"
#include "ubersim/robot_config.hpp"

namespace ubersim::report {

// The robot every experiment drives (YELLOW_0 of the scenarios below).
constexpr int kRobot = 0;
// Physics steps per radio command: the radio's 60 Hz packets at 240 Hz physics.
constexpr int kStepsPerCommand = 4;

class ExperimentSetup {
 public:
  // Reads the physics config (gravity) and the ball config; throws ConfigError.
  explicit ExperimentSetup(RigPaths paths, std::string ball = "ssl_golf_ball");

  const RigPaths& paths() const { return paths_; }
  double gravity() const { return gravity_; }  // m/s^2, GRAVITY of the physics config
  const physics::BallConfig& ball() const { return ball_; }
  RobotTypeConfig robot(const std::string& type) const;
  // LATENCY (s) of a radio profile (name or path).
  double radio_latency(const std::string& profile) const;

  // Writes a file into the work folder; returns its path.
  std::string write(const std::string& name, const std::string& text) const;

  // Division A field, one robot of `type` (YELLOW_0) at (-5.5, 0) facing +x
  // with 11 m of room ahead; the rig's ping robot (BLUE_0) and the ball parked
  // in corners.
  std::string drive_scenario(const std::string& type) const;
  // Division B field, YELLOW_0 of `type` at the centre; ping robot and ball in corners.
  std::string centre_scenario(const std::string& type) const;
  // A 44 m x 4 m carpet (a field file of its own) so that a 6.5 m/s kick
  // (37 m of roll-out) never reaches a wall; YELLOW_0 of `type` near one end.
  std::string hall_scenario(const std::string& type) const;
  static constexpr double kHallStartX = -21.0;  // m, where hall experiments put the robot

 private:
  RigPaths paths_;
  std::string ball_name_;
  double gravity_ = 0;
  physics::BallConfig ball_;
};

// One ground-truth sample of a robot.
struct RobotSample {
  double t = 0;                      // s, sim time
  double x = 0, y = 0, heading = 0;  // m, m, rad
  double vx = 0, vy = 0;             // m/s, field frame
};
// One detection of a robot on VISION.
struct RobotDetection {
  double t = 0;  // s, t_capture
  double x = 0, y = 0, heading = 0;
};
// One ground-truth sample of the ball.
struct BallSample {
  double t = 0;
  double x = 0, y = 0, z = 0;     // m
  double vx = 0, vy = 0, vz = 0;  // m/s
};

// Picks yellow robot `id` out of a state / frame; false when it is not there.
bool find_robot(const sim_state_t& state, int id, RobotSample& out);
bool find_detection(const vision_frame_t& frame, int id, RobotDetection& out);
BallSample ball_sample(const sim_state_t& state);

// A placement request: yellow robot `id` at rest at (x, y, heading); the ball
// too when `ball` is given (x, y, z, vx, vy, vz).
sim_control_t place_robot(int id, double x, double y, double heading);
void place_ball(sim_control_t& request, double x, double y, double z, double vx, double vy,
                double vz);

// Holds every robot still: zero-velocity packets for COMMAND_TIMEOUT-proof
// 0.3 s (so a lost packet or an older command cannot carry on).
void send_stop(SimRig& rig, int robot_id);

}  // namespace ubersim::report
