#pragma once
// How a robot's wheels move its chassis. Two models, chosen per robot type
// (DRIVE_MODEL) and held to the same behaviour tests:
//   jointed: wheel bodies on hinge joints with velocity motors of finite
//            torque; ODE's contacts give traction (anisotropic for omni rollers);
//   planar:  no wheel bodies; the chassis is held to the floor plane and each
//            wheel's traction, bounded by its motor and by Coulomb friction, is
//            solved per robot and applied at the wheel's contact point.
#include <deque>
#include <memory>
#include <vector>

#include "ubersim/physics/chassis_geom.hpp"
#include "ubersim/physics/geom_tag.hpp"
#include "ubersim/physics/kinematics.hpp"
#include "ubersim/physics/ode_handles.hpp"
#include "ubersim/physics/physics_config.hpp"
#include "ubersim/robot_config.hpp"

namespace ubersim::physics {

// Planar pose and field-frame velocity of a robot.
struct PlanarState {
  double x = 0, y = 0, heading = 0;  // m, m, rad
  double vx = 0, vy = 0, omega = 0;  // m/s, m/s, rad/s
};

struct DriveContext {
  dWorldID world = nullptr;
  dSpaceID space = nullptr;  // the robot's own space
  const RobotTypeConfig* type = nullptr;
  const PhysicsConfig* physics = nullptr;
  const WheelKinematics* kinematics = nullptr;
  const ChassisOutline* outline = nullptr;  // z relative to the chassis body origin
  GeomTag* chassis_tag = nullptr;
  Robot* robot = nullptr;
};

class Drive {
 public:
  virtual ~Drive() = default;
  virtual dBodyID chassis() const = 0;
  virtual dGeomID chassis_geom() const = 0;
  // Before each step: wheel speed set-points (rad/s), already within the motor's limit.
  virtual void drive(const std::vector<double>& wheel_speeds, double dt) = 0;
  // After each step.
  virtual void after_step() {}
  // Wheel speeds (rad/s) as the robot's encoders would measure them.
  virtual void measured_wheel_speeds(std::vector<double>& out) const = 0;
  // The whole robot upright at a pose, moving with a velocity, wheels rolling.
  virtual void place(const PlanarState& state) = 0;
  // Every ODE body of the robot (for safety checks).
  virtual void bodies(std::vector<dBodyID>& out) const = 0;
};

// Height of the chassis body's origin above the floor when upright (m): the
// centre of mass for the jointed model, the floor for the planar one (its
// plane-2D joint holds the body at z = 0).
double chassis_origin_height(const RobotTypeConfig& type);

std::unique_ptr<Drive> make_jointed_drive(const DriveContext& context);
std::unique_ptr<Drive> make_planar_drive(const DriveContext& context);

// Shared by both models: an upright rotation about z, by angle or by its
// cosine and sine.
void yaw_rotation(double heading, dMatrix3 R);
void yaw_rotation(double cos_heading, double sin_heading, dMatrix3 R);

// Shared by both models' place(): the chassis body upright at the pose of
// `state`, its origin `height` above the floor, moving with its planar
// velocity, no force or torque left over.
void place_chassis(dBodyID chassis, const PlanarState& state, double height);
// The wheel speeds (rad/s) that roll with the field-frame velocity of `state`.
Eigen::VectorXd rolling_wheel_speeds(const WheelKinematics& kinematics, const PlanarState& state);

}  // namespace ubersim::physics
