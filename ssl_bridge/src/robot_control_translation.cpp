#include "ubersim/ssl_bridge/robot_control_translation.hpp"

#include <cmath>
#include <string>
#include <ubersim/robot_command_t.hpp>
#include <ubersim/team_t.hpp>

#include "ubersim/ssl_bridge/units.hpp"

namespace ubersim::ssl {
namespace {

bool finite(std::initializer_list<double> values) {
  for (double v : values) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

// Fills the motion part; false (and an error) when the command is unusable.
bool translate_move(const RobotCommand& in, const std::optional<WheelMapping>& wheels,
                    robot_command_t& out, Errors& errors) {
  const std::string robot = "robot " + std::to_string(in.id());
  out.mode = robot_command_t::MODE_LOCAL_VELOCITY;  // no move command: stand still
  if (!in.has_move_command()) return true;
  const RobotMoveCommand& move = in.move_command();
  switch (move.command_case()) {
    case RobotMoveCommand::kLocalVelocity: {
      const MoveLocalVelocity& v = move.local_velocity();
      out.vx = v.forward();
      out.vy = v.left();
      out.omega = v.angular();
      break;
    }
    case RobotMoveCommand::kGlobalVelocity: {
      const MoveGlobalVelocity& v = move.global_velocity();
      out.mode = robot_command_t::MODE_GLOBAL_VELOCITY;
      out.vx = v.x();
      out.vy = v.y();
      out.omega = v.angular();
      break;
    }
    case RobotMoveCommand::kWheelVelocity: {
      if (!wheels) {
        add_error(errors, kErrorUnsupported,
                  "wheel_velocity needs a robot type with one wheel per quadrant (" + robot + ")");
        return false;
      }
      const MoveWheelVelocity& w = move.wheel_velocity();
      const std::array<double, 4> surface{w.front_right(), w.back_right(), w.back_left(),
                                          w.front_left()};
      out.mode = robot_command_t::MODE_WHEEL_SPEEDS;
      out.num_wheels = wheels->num_wheels;
      out.wheel_speeds.assign(static_cast<size_t>(wheels->num_wheels), 0.0);
      for (size_t i = 0; i < surface.size(); ++i) {
        out.wheel_speeds[static_cast<size_t>(wheels->wheel_index[i])] =
            surface[i] / wheels->wheel_radius;  // m/s at the tread -> rad/s
      }
      break;
    }
    case RobotMoveCommand::COMMAND_NOT_SET:
      break;
  }
  if (!finite({out.vx, out.vy, out.omega}) ||
      (out.mode == robot_command_t::MODE_WHEEL_SPEEDS &&
       !finite(
           {out.wheel_speeds[0], out.wheel_speeds[1], out.wheel_speeds[2], out.wheel_speeds[3]}))) {
    add_error(errors, kErrorInvalid, "non-finite velocity for " + robot + " (command dropped)");
    return false;
  }
  return true;
}

void translate_kick(const RobotCommand& in, robot_command_t& out, Errors& errors) {
  const std::string robot = "robot " + std::to_string(in.id());
  if (in.has_kick_speed()) {
    const double speed = in.kick_speed();
    const double angle = in.kick_angle();
    if (!finite({speed, angle}) || speed < 0 || angle < 0 || angle >= 90) {
      add_error(
          errors, kErrorInvalid,
          "kick_speed must be >= 0 and kick_angle in [0, 90) degrees (" + robot + ": no kick)");
    } else if (angle == 0) {
      out.kick_speed = speed;
    } else {
      out.chip_speed = speed;  // both are the ball's absolute (3D) speed
      out.chip_angle = deg_to_rad(angle);
    }
  }
  if (in.has_dribbler_speed()) {
    const double rpm = in.dribbler_speed();
    if (!std::isfinite(rpm)) {
      add_error(errors, kErrorInvalid, "non-finite dribbler_speed (" + robot + ": dribbler off)");
    } else {
      // As in the ER-Force simulator (src/amun/simulator/simrobot.cpp): only a positive speed
      // turns the dribbler; 0 or less leaves it off.
      out.dribbler_speed = rpm > 0 ? rpm_to_rad_per_s(rpm) : 0.0;
    }
  }
}

}  // namespace

std::optional<WheelMapping> wheel_mapping(const RobotTypeConfig& type) {
  if (type.wheels.size() != 4 || type.wheel_radius <= 0) return std::nullopt;
  WheelMapping mapping;
  mapping.num_wheels = 4;
  mapping.wheel_radius = type.wheel_radius;
  std::array<int, 4> seen{};
  for (size_t i = 0; i < type.wheels.size(); ++i) {
    const double front = std::cos(type.wheels[i].angle);
    const double left = std::sin(type.wheels[i].angle);
    if (front == 0 || left == 0) return std::nullopt;
    // Protocol order: front right, back right, back left, front left.
    const int slot = front > 0 ? (left < 0 ? 0 : 3) : (left < 0 ? 1 : 2);
    mapping.wheel_index[static_cast<size_t>(slot)] = static_cast<int>(i);
    ++seen[static_cast<size_t>(slot)];
  }
  for (int count : seen) {
    if (count != 1) return std::nullopt;
  }
  return mapping;
}

RobotControlTranslation translate_robot_control(const RobotControl& control, Team team,
                                                const std::optional<WheelMapping>& wheels) {
  RobotControlTranslation out;
  out.packet.team = team == Team::Yellow ? int8_t{team_t::YELLOW} : int8_t{team_t::BLUE};
  for (const RobotCommand& in : control.robot_commands()) {
    robot_command_t command{};
    command.robot_id = static_cast<int32_t>(in.id());
    if (!translate_move(in, wheels, command, out.errors)) continue;
    translate_kick(in, command, out.errors);
    out.packet.commands.push_back(command);
  }
  out.packet.num_commands = static_cast<int32_t>(out.packet.commands.size());
  return out;
}

void add_feedback(const radio_feedback_t* feedback, RobotControlResponse& response) {
  if (feedback == nullptr) return;
  for (const robot_feedback_t& robot : feedback->robots) {
    RobotFeedback* out = response.add_feedback();
    out->set_id(static_cast<uint32_t>(robot.robot_id));
    out->set_dribbler_ball_contact(robot.ball_contact);
  }
}

}  // namespace ubersim::ssl
