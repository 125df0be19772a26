#include "ubersim/robot_type_definition.hpp"

#include <cctype>
#include <sstream>

#include "ubersim/config.hpp"

namespace ubersim {

bool valid_robot_type_name(const std::string& name) {
  if (name.empty() || name.size() > kMaxRobotTypeNameLength) return false;
  for (char c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-') return false;
  }
  return true;
}

bool names_a_base_file(const std::string& text) {
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    const std::size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line.compare(first, 4, "BASE") != 0) continue;
    const std::size_t next = line.find_first_not_of(" \t", first + 4);
    if (next != std::string::npos && line[next] == '=') return true;
  }
  return false;
}

RobotTypeConfig parse_robot_type_definition(const std::string& name, const std::string& text) {
  if (!valid_robot_type_name(name)) {
    throw ConfigError(name.substr(0, kMaxRobotTypeNameLength), 0,
                      "robot type name must be 1..64 letters, digits, '_' or '-'");
  }
  if (text.size() > kMaxRobotTypeText) {
    throw ConfigError(name, 0, "robot type text longer than 16 KiB");
  }
  if (names_a_base_file(text)) {
    throw ConfigError(name, 0, "a robot type defined at run time cannot name a BASE file");
  }
  return load_robot_config(ConfigFile::parse(text, name), name);
}

}  // namespace ubersim
