#pragma once
// World and solver parameters (config/physics/*.cfg) read into plain data.
#include <cstdint>
#include <string>

#include "ubersim/config.hpp"

namespace ubersim::physics {

enum class Solver { QuickStep, Exact };
// Their words in a physics config (SOLVER).
inline constexpr EnumNames<Solver, 2> kSolverNames{
    {{"quickstep", Solver::QuickStep}, {"exact", Solver::Exact}}};

struct PhysicsConfig {
  std::string name;
  double step_rate = 0;  // Hz
  Solver solver = Solver::QuickStep;
  int solver_iterations = 0;
  double solver_sor = 0;  // unitless
  double erp = 0;         // unitless
  double cfm = 0;         // unitless
  double gravity = 0;     // m/s^2, pointing down

  double contact_max_correcting_velocity = 0;  // m/s
  double contact_surface_layer = 0;            // m
  int max_contacts = 0;                        // per pair of geoms
  double bounce_min_velocity = 0;              // m/s
  double wheel_contact_margin = 0;             // m
  double ball_robot_friction = 0;              // unitless
  double robot_robot_friction = 0;             // unitless
  double robot_robot_restitution = 0;          // unitless
  double chassis_ground_friction = 0;          // unitless
  int chassis_outline_segments = 0;
  int planar_solver_iterations = 0;

  double tip_angle = 0;          // rad
  double max_linear_speed = 0;   // m/s: a body faster than this has exploded
  double max_angular_speed = 0;  // rad/s: likewise

  double state_publish_rate = 0;       // Hz of sim time, 0 = every step
  double geometry_publish_period = 0;  // s of wall time
  double max_pacing_lag = 0;           // s of wall time
  double message_poll_period = 0;      // s of wall time between message checks, as fast as possible
  std::int64_t max_steps_per_request = 0;

  double dt() const { return 1.0 / step_rate; }
};

// Reads every key (and rejects any other). Throws ConfigError.
PhysicsConfig load_physics_config(const ConfigFile& config, const std::string& name);
PhysicsConfig load_physics_config(const std::string& config_dir, const std::string& name);

}  // namespace ubersim::physics
