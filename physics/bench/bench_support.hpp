#pragma once
// What the physics benchmarks share: the machine's load, printed beside
// figures measured on a shared machine. (Their work folder is the tests'
// TempFolder, tests/support/temp_folder.hpp.)
#include <fstream>
#include <string>

namespace ubersim::physics::bench {

// "1.23 1.10 0.98": the load averages over 1, 5 and 15 minutes.
inline std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string one, five, fifteen;
  in >> one >> five >> fifteen;
  return one + " " + five + " " + fifteen;
}

}  // namespace ubersim::physics::bench
