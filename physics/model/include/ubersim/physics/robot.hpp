#pragma once
// One robot of any configured type: chassis and drive (jointed or planar),
// on-board control (command hold and timeout, acceleration limits, inverse
// kinematics), kicker and dribbler.
#include <memory>
#include <ubersim/robot_state_t.hpp>
#include <vector>

#include "ubersim/channels.hpp"
#include "ubersim/physics/ball.hpp"
#include "ubersim/physics/drive.hpp"
#include "ubersim/physics/robot_command.hpp"

namespace ubersim::physics {

class Robot {
 public:
  Robot(dWorldID world, dSpaceID world_space, const PhysicsConfig& physics, const BallConfig& ball,
        std::shared_ptr<const RobotTypeConfig> type, Team team, int id);
  Robot(const Robot&) = delete;
  Robot& operator=(const Robot&) = delete;

  Team team() const { return team_; }
  int id() const { return id_; }
  const RobotTypeConfig& type() const { return *type_; }
  std::shared_ptr<const RobotTypeConfig> type_ptr() const { return type_; }
  dBodyID chassis() const { return drive_->chassis(); }
  dGeomID chassis_geom() const { return drive_->chassis_geom(); }
  const ChassisOutline& outline() const { return outline_; }
  const WheelKinematics& kinematics() const { return kinematics_; }

  // Upright at a pose with a field-frame velocity; the on-board set-point
  // follows (the robot keeps its command).
  void place(const PlanarState& state);
  PlanarState planar_state() const;
  // Cheaper parts of it, for every-step use: position and heading as a unit vector.
  void position(double& x, double& y) const;
  void heading_vector(double& c, double& s) const;
  // Cosine of the chassis' tilt from upright.
  double uprightness() const;
  void bodies(std::vector<dBodyID>& out) const { drive_->bodies(out); }

  // A validated command, received at sim time `now`; the robot stops when it
  // hears nothing for `timeout` s (0 = never).
  void set_command(const RobotCommand& command, double now, double timeout);
  double last_command_time() const { return last_command_time_; }

  // Control for the coming step: set-points, motors.
  void before_step(double now, double dt);
  void after_step() { drive_->after_step(); }

  // Ball against the kicker face (what the robot's ball sensor reports).
  bool ball_at_kicker(const Ball& ball) const;
  bool kicker_charged(double now) const;
  // Fires the kicker if commanded, charged and the ball is there. The ball
  // gets its new velocity at once; the chassis takes the reaction as a force
  // over the coming step. Returns true when it kicked.
  bool try_kick(Ball& ball, double now, double dt);
  // The dribbler's roller touching the ball, as a contact joint whose surface
  // moves at the roller's speed (backspin) with force capped by its motor.
  void add_dribbler_contact(const Ball& ball, double now, dWorldID world,
                            dJointGroupID group) const;
  // Perfect dribbling (the world's switch, ER-Force's simulate_dribbling =
  // false): while the dribbler is on, a ball that reaches the kicker face is
  // held there by a ball joint to the chassis; released when the dribbler goes
  // off, the robot kicks, either body is placed, or the switch goes off.
  void update_hold(const Ball& ball, double now, bool perfect_dribbling, dWorldID world);
  void release_ball() { hold_.reset(); }
  bool holds_ball() const { return hold_ != nullptr; }

  void fill_state(robot_state_t& out, const Ball& ball, double now) const;

  // The last pose that passed the world's safety checks (restored on failure).
  void remember_good_state();
  PlanarState last_good_state() const;

 private:
  // The command in force: the last one, or stop once it timed out.
  const RobotCommand& effective_command(double now) const;
  void ball_in_robot_frame(const Ball& ball, double local[3]) const;
  void add_mouth_parts(double z_bottom, double z_top, double z_mouth);

  std::shared_ptr<const RobotTypeConfig> type_;
  Team team_;
  int id_;
  const PhysicsConfig& physics_;
  double ball_radius_;
  double ball_mass_;
  WheelKinematics kinematics_;
  ChassisOutline outline_;
  GeomTag chassis_tag_;
  SpaceHandle space_;
  std::unique_ptr<Drive> drive_;
  // Around a mouth (type().has_mouth()): lip and pillars, on the chassis body.
  std::vector<ChassisOutline> front_parts_;  // reserved once: the geoms point into it
  std::vector<GeomHandle> front_geoms_;
  JointHandle hold_;  // the perfect dribbler's joint to the ball, while it holds it

  RobotCommand command_;
  double last_command_time_ = -1;                                  // s, -1 = never
  double command_timeout_ = 0;                                     // s, 0 = never
  double setpoint_vx_ = 0, setpoint_vy_ = 0, setpoint_omega_ = 0;  // field frame
  std::vector<double> wheel_targets_;
  double last_kick_time_ = -1e9;  // s
  double roller_x_ = 0;           // m, roller axis ahead of the centre (robot frame)
  double good_x_ = 0, good_y_ = 0, good_c_ = 1, good_s_ = 0;  // last good pose
  mutable std::vector<double> wheel_speed_buffer_;
};

}  // namespace ubersim::physics
