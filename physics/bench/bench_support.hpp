#pragma once
// What the benchmarks share (physics/bench, and dds_bridge/bench through its
// include path): the machine's load, printed beside figures measured on a
// shared machine, and a work folder for their runs' logs.
#include <stdlib.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>

namespace ubersim::physics::bench {

// "1.23 1.10 0.98": the load averages over 1, 5 and 15 minutes.
inline std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string one, five, fifteen;
  in >> one >> five >> fifteen;
  return one + " " + five + " " + fifteen;
}

// A fresh folder under TMPDIR (or /tmp) for a run's logs. Removed once the
// run called succeeded(); otherwise (a failed run, an exception) kept, and
// its path printed, so that the logs in it can be read.
class WorkDir {
 public:
  explicit WorkDir(const std::string& name) {
    std::string pattern = (std::filesystem::temp_directory_path() / (name + "_XXXXXX")).string();
    if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("cannot create " + pattern);
    path_ = pattern;
  }
  ~WorkDir() {
    if (!succeeded_) {
      std::fprintf(stderr, "the run's files are kept in %s\n", path_.c_str());
      return;
    }
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  WorkDir(const WorkDir&) = delete;
  WorkDir& operator=(const WorkDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  void succeeded() { succeeded_ = true; }

 private:
  std::filesystem::path path_;
  bool succeeded_ = false;
};

}  // namespace ubersim::physics::bench
