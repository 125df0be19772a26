#pragma once
// What the physics benchmarks share: the machine's load, printed beside
// figures measured on a shared machine, and a work folder for their runs.
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace ubersim::physics::bench {

// "1.23 1.10 0.98": the load averages over 1, 5 and 15 minutes.
inline std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string one, five, fifteen;
  in >> one >> five >> fifteen;
  return one + " " + five + " " + fifteen;
}

// A fresh folder under TMPDIR (or /tmp) for the runs' logs; the caller removes it.
inline std::filesystem::path make_work_dir(const std::string& name) {
  std::string pattern = (std::filesystem::temp_directory_path() / (name + "_XXXXXX")).string();
  if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("cannot create " + pattern);
  return pattern;
}

}  // namespace ubersim::physics::bench
