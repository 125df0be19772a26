#pragma once
// The CPUs a process (or thread) may run on, as the kernel lists them ("1",
// "0-1"): for the tests of where launch.sh and OnOneCpu place processes.
#include <sys/types.h>

#include <fstream>
#include <string>

namespace ubersim::test {

inline std::string allowed_cpus(pid_t pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("Cpus_allowed_list:", 0) == 0) return line.substr(line.find_last_of(" \t") + 1);
  }
  return "";
}

}  // namespace ubersim::test
