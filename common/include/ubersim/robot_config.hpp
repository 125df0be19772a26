#pragma once
// A robot type (config/robots/*.cfg) read into plain data. A new robot type is
// a new config file: physics builds the body from these values, the vision
// emulator takes its size for occlusion, the referee its radius for placement.
#include <string>
#include <vector>

#include "ubersim/config.hpp"

namespace ubersim {

enum class DriveKind { Omni, Differential };
enum class DriveModel { Jointed, Planar };
// Their words in a robot config (DRIVE, DRIVE_MODEL) and everywhere else.
inline constexpr EnumNames<DriveKind, 2> kDriveKindNames{
    {{"omni", DriveKind::Omni}, {"differential", DriveKind::Differential}}};
inline constexpr EnumNames<DriveModel, 2> kDriveModelNames{
    {{"jointed", DriveModel::Jointed}, {"planar", DriveModel::Planar}}};

struct WheelConfig {
  double angle = 0;     // rad, direction from the robot centre to the wheel (0 = forward)
  double distance = 0;  // m, robot centre to the wheel's contact point
  // Unit vector (robot frame) along which the wheel drives the robot: tangential
  // for omni wheels, forward for differential drive.
  double drive_x = 0, drive_y = 0;
};

struct RobotTypeConfig {
  std::string name;
  DriveKind drive = DriveKind::Omni;
  DriveModel model = DriveModel::Jointed;

  double mass = 0;                   // kg, whole robot
  double moment_of_inertia = 0;      // kg m^2 about the vertical axis
  double radius = 0;                 // m
  double height = 0;                 // m
  double center_of_mass_height = 0;  // m
  double front_distance = 0;         // m, centre to the flat front of the body
  double ground_clearance = 0;       // m, floor to the underside of the chassis
  // m, centre to the kicker face and dribbler, where a held ball rests
  // (KICKER_DISTANCE, default FRONT_DISTANCE). Nearer than the front, the
  // body has a mouth there: the flat front's width, from the chassis'
  // underside up to mouth_height, so the ball sits partly inside the robot.
  double kicker_distance = 0;
  double mouth_height = 0;  // m, floor to the top of the mouth (MOUTH_HEIGHT); 0 = no mouth

  std::vector<WheelConfig> wheels;
  double wheel_radius = 0;               // m
  double wheel_width = 0;                // m
  double wheel_mass = 0;                 // kg (jointed model only)
  double wheel_friction = 0;             // unitless, along the rolling direction
  double wheel_lateral_friction = 0;     // unitless, across it (small for omni rollers)
  double wheel_contact_stiffness = 0;    // N/m, tyre against floor (jointed model only)
  double wheel_contact_damping = 0;      // N s/m, likewise
  double motor_max_torque = 0;           // N m at the wheel
  double motor_max_speed = 0;            // rad/s at the wheel
  std::vector<double> caster_positions;  // m, x y pairs (differential drive)
  double caster_radius = 0;              // m, frictionless ball casters (differential drive)

  double max_speed = 0;                 // m/s, commands are clamped to it
  double max_angular_speed = 0;         // rad/s
  double max_acceleration = 0;          // m/s^2, on-board limit, 0 = none
  double max_angular_acceleration = 0;  // rad/s^2, 0 = none
  // Braking limits: for the part of a set-point change that reduces the speed
  // (MAX_BRAKE_ACCELERATION, MAX_ANGULAR_BRAKE_ACCELERATION). Default: the
  // speed-up limit above, so a type without them brakes as it speeds up.
  double max_brake_acceleration = 0;          // m/s^2, 0 = none
  double max_angular_brake_acceleration = 0;  // rad/s^2, 0 = none

  double dribbler_max_speed = 0;      // rad/s of the roller, 0 = no dribbler
  double dribbler_roller_radius = 0;  // m
  double dribbler_height = 0;         // m, roller axis above the ground
  double dribbler_width = 0;          // m
  double dribbler_max_torque = 0;     // N m on the roller

  double kick_max_speed = 0;        // m/s, 0 = no kicker
  double chip_max_speed = 0;        // m/s, 0 = cannot chip
  double chip_default_angle = 0;    // rad
  double chip_max_angle = 0;        // rad, steeper chip commands are clamped to it
  double kicker_recharge_time = 0;  // s
  double kicker_width = 0;          // m, width of the kicker face the ball must touch
  double kicker_reach = 0;  // m, largest gap between ball and face that still counts as touching

  std::size_t wheel_count() const { return wheels.size(); }
  std::size_t caster_count() const { return caster_positions.size() / 2; }
  bool has_dribbler() const { return dribbler_max_speed > 0; }
  bool has_kicker() const { return kick_max_speed > 0 || chip_max_speed > 0; }
  bool has_mouth() const { return kicker_distance < front_distance; }
};

// Reads every key of a robot file (and rejects any other). Throws ConfigError.
RobotTypeConfig load_robot_config(const ConfigFile& config, const std::string& name);
RobotTypeConfig load_robot_config(const std::string& config_dir, const std::string& name);

}  // namespace ubersim
