#pragma once
// The whole of a file as a string, "" when it cannot be read: a run's logs, a
// page the viewer serves, a /proc file.
#include <fstream>
#include <sstream>
#include <string>

namespace ubersim::test {

inline std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace ubersim::test
