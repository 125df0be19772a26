#pragma once
// A robot type defined at run time (SIM_CONTROL DEFINE_ROBOT_TYPE): a name and
// the text of a robot config file, read by the same reader as config/robots/,
// so every key is checked. Physics builds robots from it; the vision emulator
// takes the size. The text comes from the network, so it is bounded and may
// not name a BASE file (the reader would open a file the sender chose).
#include <string>

#include "ubersim/robot_config.hpp"

namespace ubersim {

inline constexpr std::size_t kMaxRobotTypeNameLength = 64;
inline constexpr std::size_t kMaxRobotTypeText =
    std::size_t{16} * 1024;  // bytes; a robot file is ~3 KB

// 1..64 letters, digits, '_' or '-': a name, never a path. Robot type names
// from the network (a definition, a SIM_STATE's robot_type) must be one.
bool valid_robot_type_name(const std::string& name);

// True when the text has a "BASE = ..." line, which the config reader would
// follow to a file: texts from the network are checked with it before parsing.
bool names_a_base_file(const std::string& text);

// Throws ConfigError (file = the type's name) for a bad name or text.
RobotTypeConfig parse_robot_type_definition(const std::string& name, const std::string& text);

}  // namespace ubersim
