#pragma once
// The one check of a robot command's contents, for every part that takes
// commands: the radio emulator (a team's packets), physics (SIM_COMMANDS) and
// the Python module (the commands array). What can be wrong with a command is
// decided here once; each part says what it does about it (the radio drops
// the entry and counts it by kind, physics drops the command and counts it,
// the Python module raises).
#include <cstddef>
#include <optional>
#include <string>
#include <ubersim/robot_command_t.hpp>

namespace ubersim {

// A radio's sanity limits (a radio profile's RADIO_MAX_*): beyond them a
// radio's firmware refuses a command rather than clamping it.
struct CommandLimits {
  double speed = 0;           // m/s, |(vx, vy)|
  double angular_speed = 0;   // rad/s, |omega|
  double wheel_speed = 0;     // rad/s, |each wheel speed| in wheel-speed mode
  double kick_speed = 0;      // m/s, flat and chip kick speed
  double dribbler_speed = 0;  // rad/s, |dribbler roller speed|
};

enum class CommandFault {
  UnknownMode,  // robot_command_t.mode is none of MODE_*
  NonFinite,    // NaN or Inf in a value the mode reads
  AbsurdValue,  // beyond the sanity limits, a negative kick speed or a bad chip angle
  WheelCount,   // wheel-speed mode with a wheel count that is not the robot's
};

struct CommandFaultFound {
  CommandFault fault;
  std::string detail;  // what is wrong, for the log or the exception
};

// What is wrong with `command` for a robot with `wheels` wheels (0: not known,
// then any wheel count but none goes), in this order: an unknown mode, a NaN
// or Inf (wheel speeds only in wheel-speed mode, the only one that reads
// them), with `limits` a value beyond them (nullptr: no sanity limits; physics
// clamps to the robot's own), a wheel-speed command for another number of
// wheels. Nothing when the command may be applied.
std::optional<CommandFaultFound> find_command_fault(const robot_command_t& command,
                                                    std::size_t wheels,
                                                    const CommandLimits* limits);

}  // namespace ubersim
