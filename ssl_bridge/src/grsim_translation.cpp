#include "ubersim/ssl_bridge/grsim_translation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <ubersim/team_t.hpp>

#include "ubersim/ssl_bridge/units.hpp"

namespace ubersim::ssl {
namespace {

// grSim acts on a kick speed above this (SSLWorld::recvActions).
constexpr double kGrsimKickThreshold = 0.0001;  // m/s
// ... and calls a kick a chip from this upward speed on (Kicker::kick).
constexpr double kGrsimChipStatusSpeed = 1.0;  // m/s
// The radio takes a chip angle below 90 degrees; grSim's straight-up kick
// (kickspeedx 0) becomes this.
constexpr double kSteepestChip = 89.0 * (kPi / 180.0);  // rad

// grSim's wheels 1..4 sit at its default angles 60, 135, 225 and 300 degrees
// (src/configwidget.cpp, Wheel1Angle..Wheel4Angle): front left, back left,
// back right, front right. Their slots in WheelMapping (FR, BR, BL, FL).
constexpr std::array<int, 4> kGrsimWheelSlot{3, 2, 1, 0};

bool finite(std::initializer_list<double> values) {
  return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

bool translate_wheels(const grSim_Robot_Command& in, const GrsimTranslationSettings& settings,
                      const robot_command_t* previous, robot_command_t& out, Errors& errors) {
  const std::string robot = "robot " + std::to_string(in.id());
  if (!settings.wheels) {
    add_error(errors, kErrorUnsupported,
              "wheelsspeed needs a robot type with one wheel per quadrant (" + robot + ")");
    return false;
  }
  const WheelMapping& wheels = *settings.wheels;
  out.mode = robot_command_t::MODE_WHEEL_SPEEDS;
  out.num_wheels = wheels.num_wheels;
  const bool keep = previous != nullptr && previous->mode == robot_command_t::MODE_WHEEL_SPEEDS &&
                    previous->num_wheels == wheels.num_wheels;
  out.wheel_speeds = keep ? previous->wheel_speeds
                          : std::vector<double>(static_cast<size_t>(wheels.num_wheels), 0.0);
  const std::array<std::pair<bool, float>, 4> given{{{in.has_wheel1(), in.wheel1()},
                                                     {in.has_wheel2(), in.wheel2()},
                                                     {in.has_wheel3(), in.wheel3()},
                                                     {in.has_wheel4(), in.wheel4()}}};
  for (size_t i = 0; i < given.size(); ++i) {
    if (!given[i].first) continue;
    const double speed = given[i].second;  // rad/s, positive turns the robot counter-clockwise
    if (!std::isfinite(speed)) {
      add_error(errors, kErrorInvalid, "non-finite wheel speed (" + robot + ": command dropped)");
      return false;
    }
    const auto slot = static_cast<size_t>(kGrsimWheelSlot[i]);
    out.wheel_speeds[static_cast<size_t>(wheels.wheel_index[slot])] = speed;
  }
  return true;
}

// grSim kicks when either speed is above its threshold: the ball leaves with
// kickspeedx along the robot's heading and kickspeedz upwards.
GrsimKick translate_kick(double kick_x, double kick_z, robot_command_t& out) {
  if (!(kick_x > kGrsimKickThreshold || kick_z > kGrsimKickThreshold)) return GrsimKick::None;
  if (kick_z <= kGrsimKickThreshold) {
    out.kick_speed = kick_x;
    return GrsimKick::Flat;
  }
  const double along = std::max(0.0, kick_x);
  out.chip_speed = std::hypot(along, kick_z);
  out.chip_angle = std::min(std::atan2(kick_z, along), kSteepestChip);
  return kick_z >= kGrsimChipStatusSpeed ? GrsimKick::Chip : GrsimKick::Flat;
}

}  // namespace

std::optional<GrsimRobotCommand> translate_grsim_robot_command(
    const grSim_Robot_Command& in, const GrsimTranslationSettings& settings,
    const robot_command_t* previous, Errors& errors) {
  GrsimRobotCommand result{};
  robot_command_t& out = result.command;
  out.robot_id = static_cast<int32_t>(in.id());
  out.mode = robot_command_t::MODE_LOCAL_VELOCITY;
  if (in.has_wheelsspeed() && in.wheelsspeed()) {
    if (!translate_wheels(in, settings, previous, out, errors)) return std::nullopt;
  } else {
    // Unset velocities are 0, as in grSim.
    out.vx = in.has_veltangent() ? in.veltangent() : 0.0;
    out.vy = in.has_velnormal() ? in.velnormal() : 0.0;
    out.omega = in.has_velangular() ? in.velangular() : 0.0;
  }
  const double kick_x = in.has_kickspeedx() ? in.kickspeedx() : 0.0;
  const double kick_z = in.has_kickspeedz() ? in.kickspeedz() : 0.0;
  if (!finite({out.vx, out.vy, out.omega, kick_x, kick_z})) {
    add_error(errors, kErrorInvalid,
              "non-finite velocity or kick speed (robot " + std::to_string(in.id()) +
                  ": command dropped)");
    return std::nullopt;
  }
  result.kick = translate_kick(kick_x, kick_z, out);
  // grSim's spinner is on or off; on, its roller holds a touching ball.
  out.dribbler_speed = in.has_spinner() && in.spinner() ? settings.spinner_speed : 0.0;
  return result;
}

SimulatorCommand grsim_replacement_command(const grSim_Replacement& in, const sim_state_t* state,
                                           Errors& errors) {
  SimulatorCommand command;
  SimulatorControl& control = *command.mutable_control();
  for (const grSim_RobotReplacement& robot : in.robots()) {
    if (!robot.has_id() || robot.id() >= kGrsimMaxRobots) {
      add_error(errors, kErrorInvalid,
                "robot replacement without an id below " + std::to_string(kGrsimMaxRobots) +
                    " (left out, as grSim does)");
      continue;
    }
    TeleportRobot& out = *control.add_teleport_robot();
    out.mutable_id()->set_id(robot.id());
    out.mutable_id()->set_team(robot.has_yellowteam() && robot.yellowteam() ? YELLOW : BLUE);
    // grSim reads an unset coordinate as 0 and stops the robot (resetRobot).
    out.set_x(static_cast<float>(robot.has_x() ? robot.x() : 0.0));
    out.set_y(static_cast<float>(robot.has_y() ? robot.y() : 0.0));
    out.set_orientation(static_cast<float>(deg_to_rad(robot.has_dir() ? robot.dir() : 0.0)));
    out.set_v_x(0);
    out.set_v_y(0);
    out.set_v_angular(0);
    out.set_present(!robot.has_turnon() || robot.turnon());
  }
  if (in.has_ball()) {
    const grSim_BallReplacement& ball = in.ball();
    TeleportBall& out = *control.mutable_teleport_ball();
    // Unset: where the ball is and how it moves now, as in grSim.
    if (ball.has_x()) out.set_x(static_cast<float>(ball.x()));
    if (ball.has_y()) out.set_y(static_cast<float>(ball.y()));
    const double* current = state != nullptr ? state->ball.linear_velocity : nullptr;
    out.set_vx(static_cast<float>(ball.has_vx() ? ball.vx() : (current ? current[0] : 0.0)));
    out.set_vy(static_cast<float>(ball.has_vy() ? ball.vy() : (current ? current[1] : 0.0)));
    out.set_vz(0);
  }
  return command;
}

}  // namespace ubersim::ssl
