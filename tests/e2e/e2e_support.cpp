#include "e2e_support.hpp"

#include <unistd.h>

#include <regex>
#include <stdexcept>
#include <thread>

#include "ubersim/common_options.hpp"

namespace e2e {

std::string source_dir() {
  return UBERSIM_SOURCE_DIR;
}
std::string bin_dir() {
  return UBERSIM_BIN_DIR;
}

namespace {

std::vector<std::string> launch_argv(const std::vector<std::string>& options, const TempDir& dir) {
  // The launch script finds the programs through UBERSIM_BUILD_DIR.
  const std::string build_dir = std::filesystem::path(bin_dir()).parent_path().string();
  ::setenv("UBERSIM_BUILD_DIR", build_dir.c_str(), 1);
  std::vector<std::string> argv{"/bin/bash", source_dir() + "/tools/launch.sh", "--log-dir",
                                dir.path("logs")};
  argv.insert(argv.end(), options.begin(), options.end());
  return argv;
}

}  // namespace

Launch::Launch(const std::vector<std::string>& options, const TempDir& dir)
    : script_(launch_argv(options, dir), dir.path("launch.out")) {}

Launch::~Launch() {
  if (script_.running()) script_.stop(5, SIGINT);
}

std::map<std::string, pid_t> Launch::processes(double timeout_s) {
  static const std::regex line(R"(^\s+(\S+)\s+pid (\d+)\s+log )");
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < deadline) {
    const std::string text = output();
    if (text.find("Ctrl-C stops everything") != std::string::npos) {
      std::map<std::string, pid_t> found;
      std::istringstream lines(text);
      std::string l;
      std::smatch match;
      while (std::getline(lines, l)) {
        if (std::regex_search(l, match, line)) found[match[1]] = std::stoi(match[2]);
      }
      return found;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  throw std::runtime_error("launch script did not start its processes: " + output());
}

CpuHog::CpuHog() {
  const long cores = std::max(1L, ::sysconf(_SC_NPROCESSORS_ONLN));
  for (long i = 0; i < cores; ++i) {
    hogs_.push_back(std::make_unique<ubersim::test::ChildProcess>(
        std::vector<std::string>{"/bin/sh", "-c", "while :; do :; done"}, ""));
  }
}

std::vector<uint8_t> encode(const ubersim::vision_frame_t& frame) {
  std::vector<uint8_t> bytes(static_cast<size_t>(frame.getEncodedSize()));
  frame.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

VisionListener::VisionListener() : bus_(ubersim::with_receive_buffer(ubersim::default_lcm_url())) {
  bus_.subscribe<ubersim::vision_frame_t>("VISION", [this](const ubersim::vision_frame_t& f) {
    frames_.push_back(f);
    bytes_.push_back(encode(f));
  });
}

bool VisionListener::run_until(const std::function<bool()>& done, double timeout_s) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (!done() && std::chrono::steady_clock::now() < deadline) bus_.wait_and_handle(20);
  return done();
}

void VisionListener::run_for(double seconds) {
  run_until([] { return false; }, seconds);
}

}  // namespace e2e
