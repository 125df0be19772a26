#pragma once
// A robot command after validation: every value finite and within the robot's
// limits. Only these ever reach the physics.
#include <array>
#include <cstdint>
#include <string>
#include <ubersim/robot_command_t.hpp>
#include <vector>

#include "ubersim/command_check.hpp"
#include "ubersim/robot_config.hpp"

namespace ubersim::physics {

enum class CommandMode { LocalVelocity, GlobalVelocity, WheelSpeeds };

struct RobotCommand {
  CommandMode mode = CommandMode::LocalVelocity;
  double vx = 0, vy = 0, omega = 0;  // m/s, m/s, rad/s (robot or field frame per mode)
  std::vector<double> wheel_speeds;  // rad/s, WheelSpeeds mode
  double kick_speed = 0;             // m/s, 0 = none
  double chip_speed = 0;             // m/s, 0 = none
  double chip_angle = 0;             // rad, resolved (never 0 when chip_speed > 0)
  double dribbler_speed = 0;         // rad/s of the roller
};

// The limits of a robot type a command can go beyond (then it is applied at the limit).
enum class CommandLimit {
  Speed,
  AngularSpeed,
  WheelSpeed,
  KickSpeed,
  ChipSpeed,
  ChipAngle,
  DribblerSpeed,
  NegativeKick,       // a negative kick or chip speed: no kick
  NegativeChipAngle,  // replaced by the type's default angle
  Count
};
constexpr std::size_t kCommandLimits = static_cast<std::size_t>(CommandLimit::Count);
const char* command_limit_name(CommandLimit limit);

struct CommandCheck {
  bool accepted = false;         // false: dropped, keep the previous command
  bool clamped = false;          // accepted with values changed to fit the robot
  std::uint32_t limits_hit = 0;  // bit (1 << CommandLimit) for each limit applied
  std::string problem;           // what was wrong, for the log
  RobotCommand command;
};

// Commands applied at a robot type's limit: in all, and per limit (a command may count under
// several).
struct ClampCounts {
  std::uint64_t commands = 0;
  std::array<std::uint64_t, kCommandLimits> by_limit{};

  void add(const CommandCheck& check);
  // "12 (kick speed 10, speed 2)", or "0".
  std::string text() const;
};

// Drops a command find_command_fault finds wrong (a non-finite value, an
// unknown mode or the wrong number of wheel speeds: ubersim/command_check.hpp,
// the check every part shares); clamps values beyond the robot's limits.
CommandCheck check_command(const robot_command_t& raw, const RobotTypeConfig& robot);

}  // namespace ubersim::physics
