#pragma once
// The benchmark's baseline: the same scene (field, ball, robots of the same
// sizes, masses, wheels and joints) stepped by bare ODE calls, with no
// framework and no messages: one near callback, fixed surface parameters,
// motor set-points written straight into the joints. What ubersim adds on
// top of this is what the benchmark calls its overhead.
#include <ode/ode.h>

#include <vector>

#include "ubersim/physics/world.hpp"

namespace ubersim::physics::bench {

class BareOdeScene {
 public:
  BareOdeScene(const WorldSetup& setup, DriveModel model);
  ~BareOdeScene();
  BareOdeScene(const BareOdeScene&) = delete;
  BareOdeScene& operator=(const BareOdeScene&) = delete;

  std::size_t robot_count() const { return robots_.size(); }
  // Robot-frame velocity set-point (m/s, m/s, rad/s).
  void command(std::size_t robot, double vx, double vy, double omega);
  void step();

 private:
  struct Wheel {
    dBodyID body = nullptr;
    dJointID hinge = nullptr;
    double x = 0, y = 0, dx = 0, dy = 0;  // contact point and drive direction, robot frame
  };
  struct Robot {
    dBodyID chassis = nullptr;
    dSpaceID space = nullptr;
    std::vector<Wheel> wheels;
    double wheel_radius = 0;
    double mass = 0, inertia = 0, max_force = 0;
    double max_acceleration = 0, max_angular_acceleration = 0;
    double target[3] = {0, 0, 0};    // robot-frame velocity command
    double setpoint[3] = {0, 0, 0};  // field-frame, ramped at the robot's acceleration limit
  };
  static void near_callback(void* data, dGeomID a, dGeomID b);

  DriveModel model_;
  double dt_;
  dWorldID world_ = nullptr;
  dSpaceID space_ = nullptr;
  dSpaceID static_space_ = nullptr;
  dJointGroupID contacts_ = nullptr;
  dBodyID ball_ = nullptr;
  std::vector<Robot> robots_;
};

}  // namespace ubersim::physics::bench
