#include "ubersim/robot_config.hpp"

#include <algorithm>
#include <cmath>

#include "ubersim/angles.hpp"
#include "ubersim/config_paths.hpp"

namespace ubersim {

namespace {

// DRIVE and DRIVE_MODEL.
void read_drive(const ConfigFile& config, RobotTypeConfig& r) {
  r.drive = config.choice("DRIVE", kDriveKindNames);
  r.model = config.choice("DRIVE_MODEL", kDriveModelNames);
}

// The chassis: mass, size, and where the kicker sits in its front.
void read_body(const ConfigFile& config, RobotTypeConfig& r) {
  r.mass = config.real_in("MASS", 0.01, 100.0);
  r.moment_of_inertia = config.real_in("MOMENT_OF_INERTIA", 1e-6, 100.0);
  r.radius = config.real_in("RADIUS", 0.01, 1.0);
  r.height = config.real_in("HEIGHT", 0.01, 1.0);
  r.center_of_mass_height = config.real_in("CENTER_OF_MASS_HEIGHT", 0.0, r.height);
  r.front_distance = config.real_in("FRONT_DISTANCE", 0.0, r.radius);
  r.ground_clearance = config.real_in("GROUND_CLEARANCE", 0.0, r.height / 2);
  // Optional: the kicker and dribbler set back into a mouth of the front.
  r.kicker_distance = config.has("KICKER_DISTANCE")
                          ? config.real_in("KICKER_DISTANCE", 0.0, r.front_distance)
                          : r.front_distance;
  if (config.has("MOUTH_HEIGHT")) {
    r.mouth_height = config.real_in("MOUTH_HEIGHT", r.ground_clearance, r.height);
  } else if (r.has_mouth()) {
    config.fail("KICKER_DISTANCE",
                "a kicker set back from FRONT_DISTANCE needs MOUTH_HEIGHT (m, floor to the top of "
                "the opening it sits in)");
  }
}

// Where the wheels are and which way each pushes.
void read_wheel_layout(const ConfigFile& config, RobotTypeConfig& r) {
  const auto angles = config.reals("WHEEL_ANGLES_DEG");
  const std::size_t expected_wheels = r.drive == DriveKind::Differential ? 2 : 0;
  if (expected_wheels != 0 && angles.size() != expected_wheels) {
    config.fail("WHEEL_ANGLES_DEG",
                "a differential drive has exactly 2 wheels, got " + std::to_string(angles.size()));
  }
  if (r.drive == DriveKind::Omni && angles.size() < 3) {
    config.fail("WHEEL_ANGLES_DEG",
                "an omni drive needs at least 3 wheels, got " + std::to_string(angles.size()));
  }
  // One distance for every wheel, or one per wheel (any placement is allowed).
  const auto distances = config.reals("WHEEL_DISTANCE");
  if (distances.size() != 1 && distances.size() != angles.size()) {
    config.fail("WHEEL_DISTANCE", "expected 1 value or one per wheel (" +
                                      std::to_string(angles.size()) + "), got " +
                                      std::to_string(distances.size()));
  }
  for (double d : distances) {
    if (!(d >= 0.001 && d <= r.radius)) {
      config.fail("WHEEL_DISTANCE", "expected values in [0.001, " + std::to_string(r.radius) +
                                        "] m (inside the robot)");
    }
  }
  for (std::size_t i = 0; i < angles.size(); ++i) {
    const double angle_deg = angles[i];
    WheelConfig w;
    w.angle = angle_deg * kDegToRad;
    w.distance = distances.size() == 1 ? distances[0] : distances[i];
    if (r.drive == DriveKind::Omni) {
      // Positive wheel speed pushes the robot counter-clockwise about its centre.
      w.drive_x = -std::sin(w.angle);
      w.drive_y = std::cos(w.angle);
    } else {
      w.drive_x = 1.0;
      w.drive_y = 0.0;
    }
    r.wheels.push_back(w);
  }
}

// Wheels, motors and (differential drive) casters.
void read_wheels_and_motors(const ConfigFile& config, RobotTypeConfig& r) {
  r.wheel_radius = config.real_in("WHEEL_RADIUS", 0.001, 0.5);
  r.wheel_width = config.real_in("WHEEL_WIDTH", 0.001, 0.5);
  r.wheel_mass = config.real_in("WHEEL_MASS", 0.001, 10.0);
  r.wheel_friction = config.real_in("WHEEL_FRICTION", 0.0, 10.0);
  r.wheel_lateral_friction = config.real_in("WHEEL_LATERAL_FRICTION", 0.0, 10.0);
  r.wheel_contact_stiffness = config.real_in("WHEEL_CONTACT_STIFFNESS", 100.0, 1e9);
  r.wheel_contact_damping = config.real_in("WHEEL_CONTACT_DAMPING", 0.0, 1e7);
  r.motor_max_torque = config.real_in("MOTOR_MAX_TORQUE", 0.0, 100.0);
  r.motor_max_speed = config.real_in("MOTOR_MAX_SPEED", 0.0, 10000.0);
  if (r.drive == DriveKind::Differential) {
    r.caster_positions = config.reals("CASTER_POSITIONS");
    if (r.caster_positions.empty() || r.caster_positions.size() % 2 != 0) {
      config.fail("CASTER_POSITIONS", "expected x y pairs (m)");
    }
    for (std::size_t i = 0; i < r.caster_positions.size(); i += 2) {
      if (std::hypot(r.caster_positions[i], r.caster_positions[i + 1]) > r.radius) {
        config.fail("CASTER_POSITIONS",
                    "caster " + std::to_string(i / 2) + " lies outside the robot");
      }
    }
    r.caster_radius = config.real_in("CASTER_RADIUS", 0.001, r.height / 2);
  }
}

// What the robot's on-board controller allows.
void read_motion_limits(const ConfigFile& config, RobotTypeConfig& r) {
  r.max_speed = config.real_in("MAX_SPEED", 0.0, 20.0);
  r.max_angular_speed = config.real_in("MAX_ANGULAR_SPEED", 0.0, 200.0);
  r.max_acceleration = config.real_in("MAX_ACCELERATION", 0.0, 100.0);
  r.max_angular_acceleration = config.real_in("MAX_ANGULAR_ACCELERATION", 0.0, 1000.0);
  // Optional: a robot that brakes harder (or softer) than it speeds up.
  r.max_brake_acceleration = config.has("MAX_BRAKE_ACCELERATION")
                                 ? config.real_in("MAX_BRAKE_ACCELERATION", 0.0, 100.0)
                                 : r.max_acceleration;
  r.max_angular_brake_acceleration =
      config.has("MAX_ANGULAR_BRAKE_ACCELERATION")
          ? config.real_in("MAX_ANGULAR_BRAKE_ACCELERATION", 0.0, 1000.0)
          : r.max_angular_acceleration;
}

void read_dribbler(const ConfigFile& config, RobotTypeConfig& r) {
  r.dribbler_max_speed = config.real_in("DRIBBLER_MAX_SPEED", 0.0, 10000.0);
  r.dribbler_roller_radius = config.real_in("DRIBBLER_ROLLER_RADIUS", 0.0, 0.1);
  r.dribbler_height = config.real_in("DRIBBLER_HEIGHT", 0.0, r.height);
  r.dribbler_width = config.real_in("DRIBBLER_WIDTH", 0.0, 2 * r.radius);
  r.dribbler_max_torque = config.real_in("DRIBBLER_MAX_TORQUE", 0.0, 10.0);
  if (r.dribbler_max_speed > 0) {
    if (r.dribbler_roller_radius <= 0)
      config.fail("DRIBBLER_ROLLER_RADIUS", "a dribbler needs a roller");
    if (r.dribbler_max_torque <= 0) config.fail("DRIBBLER_MAX_TORQUE", "a dribbler needs torque");
    if (r.dribbler_width <= 0) config.fail("DRIBBLER_WIDTH", "a dribbler needs a width");
  }
}

// The kicker, and that kicker and dribbler fit the flat front.
void read_kicker(const ConfigFile& config, RobotTypeConfig& r) {
  r.kick_max_speed = config.real_in("KICK_MAX_SPEED", 0.0, 20.0);
  r.chip_max_speed = config.real_in("CHIP_MAX_SPEED", 0.0, 20.0);
  r.chip_default_angle = config.real_in("CHIP_DEFAULT_ANGLE_DEG", 0.0, 89.0) * kDegToRad;
  r.chip_max_angle = config.real_in("CHIP_MAX_ANGLE_DEG", 0.0, 89.0) * kDegToRad;
  if (r.chip_default_angle > r.chip_max_angle) {
    config.fail("CHIP_DEFAULT_ANGLE_DEG", "the default chip angle exceeds CHIP_MAX_ANGLE_DEG");
  }
  r.kicker_recharge_time = config.real_in("KICKER_RECHARGE_TIME", 0.0, 60.0);
  r.kicker_width = config.real_in("KICKER_WIDTH", 0.0, 2 * r.radius);
  r.kicker_reach = config.real_in("KICKER_REACH", 0.0, r.radius);
  const double front_half_width =
      std::sqrt(std::max(0.0, r.radius * r.radius - r.front_distance * r.front_distance));
  if (r.kicker_width / 2 > front_half_width + 1e-9) {
    config.fail("KICKER_WIDTH", "wider than the flat front (" +
                                    std::to_string(2 * front_half_width) + " m at FRONT_DISTANCE)");
  }
  if (r.dribbler_width / 2 > front_half_width + 1e-9) {
    config.fail("DRIBBLER_WIDTH", "wider than the flat front (" +
                                      std::to_string(2 * front_half_width) +
                                      " m at FRONT_DISTANCE)");
  }
}

void check_jointed_masses(const ConfigFile& config, RobotTypeConfig& r) {
  if (r.model == DriveModel::Jointed) {
    // The jointed model carries the wheels as bodies of their own: the chassis
    // gets what is left of the robot's mass and inertia.
    const double wheels_mass = r.wheel_mass * static_cast<double>(r.wheels.size());
    if (wheels_mass >= r.mass) {
      config.fail("WHEEL_MASS", "the wheels weigh as much as the whole robot (MASS)");
    }
    double wheels_inertia = 0;
    for (const auto& w : r.wheels) {
      wheels_inertia +=
          r.wheel_mass * (w.distance * w.distance + r.wheel_radius * r.wheel_radius / 2);
    }
    if (wheels_inertia >= r.moment_of_inertia) {
      config.fail("MOMENT_OF_INERTIA", "smaller than the wheels' own share (" +
                                           std::to_string(wheels_inertia) + " kg m^2)");
    }
  }
}

}  // namespace

RobotTypeConfig load_robot_config(const ConfigFile& config, const std::string& name) {
  RobotTypeConfig r;
  r.name = name;
  // Always in this order: of several bad keys, the first met here is reported.
  read_drive(config, r);
  read_body(config, r);
  read_wheel_layout(config, r);
  read_wheels_and_motors(config, r);
  read_motion_limits(config, r);
  read_dribbler(config, r);
  read_kicker(config, r);
  check_jointed_masses(config, r);
  config.require_all_used();
  return r;
}

RobotTypeConfig load_robot_config(const std::string& config_dir, const std::string& name) {
  const auto path = resolve_config(config_dir, "robots", name);
  return load_robot_config(ConfigFile::load(path), path.stem().string());
}

}  // namespace ubersim
