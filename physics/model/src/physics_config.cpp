#include "ubersim/physics/physics_config.hpp"

#include <cmath>

#include "ubersim/angles.hpp"
#include "ubersim/config_paths.hpp"

namespace ubersim::physics {

PhysicsConfig load_physics_config(const ConfigFile& config, const std::string& name) {
  PhysicsConfig p;
  p.name = name;
  p.step_rate = config.real_in("STEP_RATE", 10.0, 100000.0);
  p.solver = config.choice("SOLVER", kSolverNames);
  p.solver_iterations = static_cast<int>(config.integer_in("SOLVER_ITERATIONS", 1, 1000));
  p.solver_sor = config.real_in("SOLVER_SOR", 0.1, 2.0);
  p.erp = config.real_in("ERP", 0.0, 1.0);
  p.cfm = config.real_in("CFM", 0.0, 1.0);
  p.gravity = config.real_in("GRAVITY", 0.1, 100.0);

  p.contact_max_correcting_velocity = config.real_in("CONTACT_MAX_CORRECTING_VELOCITY", 0.0, 100.0);
  p.contact_surface_layer = config.real_in("CONTACT_SURFACE_LAYER", 0.0, 0.01);
  p.max_contacts = static_cast<int>(config.integer_in("MAX_CONTACTS", 1, 64));
  p.bounce_min_velocity = config.real_in("BOUNCE_MIN_VELOCITY", 0.0, 10.0);
  p.wheel_contact_margin = config.real_in("WHEEL_CONTACT_MARGIN", 0.0, 0.01);
  p.ball_robot_friction = config.real_in("BALL_ROBOT_FRICTION", 0.0, 10.0);
  p.robot_robot_friction = config.real_in("ROBOT_ROBOT_FRICTION", 0.0, 10.0);
  p.robot_robot_restitution = config.real_in("ROBOT_ROBOT_RESTITUTION", 0.0, 1.0);
  p.chassis_ground_friction = config.real_in("CHASSIS_GROUND_FRICTION", 0.0, 10.0);
  p.chassis_outline_segments =
      static_cast<int>(config.integer_in("CHASSIS_OUTLINE_SEGMENTS", 6, 128));
  p.planar_solver_iterations =
      static_cast<int>(config.integer_in("PLANAR_SOLVER_ITERATIONS", 1, 1000));

  p.tip_angle = config.real_in("TIP_ANGLE_DEG", 5.0, 90.0) * kDegToRad;
  p.max_linear_speed = config.real_in("MAX_LINEAR_SPEED", 1.0, 1e6);
  p.max_angular_speed = config.real_in("MAX_ANGULAR_SPEED", 1.0, 1e7);

  p.state_publish_rate = config.real_in("STATE_PUBLISH_RATE", 0.0, p.step_rate);
  p.geometry_publish_period = config.real_in("GEOMETRY_PUBLISH_PERIOD", 0.01, 3600.0);
  p.max_pacing_lag = config.real_in("MAX_PACING_LAG", 0.001, 60.0);
  p.message_poll_period = config.real_in("MESSAGE_POLL_PERIOD", 0.0, 1.0);
  p.max_steps_per_request = config.integer("MAX_STEPS_PER_REQUEST");
  if (p.max_steps_per_request < 1) config.fail("MAX_STEPS_PER_REQUEST", "expected at least 1");
  config.require_all_used();
  return p;
}

PhysicsConfig load_physics_config(const std::string& config_dir, const std::string& name) {
  const auto path = resolve_config(config_dir, "physics", name);
  return load_physics_config(ConfigFile::load(path), path.stem().string());
}

}  // namespace ubersim::physics
