#pragma once
// What the end-to-end tests share: the launch script as a real process, and
// listeners on real LCM (each test binary runs in its own network namespace,
// see tests/run_isolated.sh).
#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <ubersim/vision_frame_t.hpp>
#include <vector>

#include "child_process.hpp"
#include "temp_dir.hpp"
#include "ubersim/message_bus.hpp"

namespace e2e {

std::string source_dir();  // the repository root
std::string bin_dir();     // where the programs are built

using TempDir = ubersim::test::TempDir;

// tools/launch.sh with the given options, run as a user would.
class Launch {
 public:
  Launch(const std::vector<std::string>& options, const TempDir& dir);
  // Ctrl-C, as a user would: the script stops what it started. (A test that
  // failed half-way would otherwise leave the processes running.)
  ~Launch();
  Launch(const Launch&) = delete;
  Launch& operator=(const Launch&) = delete;
  // pid of each process the script started, by name, read from its output.
  std::map<std::string, pid_t> processes(double timeout_s = 10);
  ubersim::test::ChildProcess& script() { return script_; }
  std::string output() const { return script_.log(); }

 private:
  ubersim::test::ChildProcess script_;
};

// Everything published on VISION, in arrival order, with its encoded bytes.
class VisionListener {
 public:
  VisionListener();
  // Handles messages until `done` or the timeout; returns done().
  bool run_until(const std::function<bool()>& done, double timeout_s);
  void run_for(double seconds);
  const std::vector<ubersim::vision_frame_t>& frames() const { return frames_; }
  const std::vector<std::vector<uint8_t>>& bytes() const { return bytes_; }
  ubersim::MessageBus& bus() { return bus_; }

 private:
  ubersim::MessageBus bus_;
  std::vector<ubersim::vision_frame_t> frames_;
  std::vector<std::vector<uint8_t>> bytes_;
};

std::vector<uint8_t> encode(const ubersim::vision_frame_t& frame);

// Busy loops on every core until destroyed: a loaded machine.
class CpuHog {
 public:
  CpuHog();

 private:
  std::vector<std::unique_ptr<ubersim::test::ChildProcess>> hogs_;
};

}  // namespace e2e
