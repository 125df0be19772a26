// As fast as possible (tools/launch.sh --speed 0) with the 4-camera `modern`
// profile, 2 x 11 planar: physics waits for the vision emulator, so no frame
// is lost even when the vision is stopped for a while; a loss that happens
// anyway (the vision stopped for longer than physics waits) is counted in the
// vision's summary and named on the launch script's terminal
// (docs/vision.md, "As fast as possible").
#include <gtest/gtest.h>
#include <signal.h>

#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <thread>

#include "e2e_support.hpp"
#include "ubersim/vision_backpressure.hpp"

namespace e2e {
namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The vision's exit summary, e.g. {"frames lost": 0, "captured": 19201}.
std::map<std::string, long> vision_summary(const TempDir& dir) {
  const std::string log = read_text(dir.path("logs/vision.log"));
  std::map<std::string, long> counts;
  const auto at = log.find("summary:");
  if (at == std::string::npos) return counts;
  const std::string line = log.substr(at + 8, log.find('\n', at) - at - 8);
  static const std::regex item(R"(([a-z ]+?) (\d+)(?:[,;]|$))");
  for (std::sregex_iterator it(line.begin(), line.end(), item), end; it != end; ++it) {
    std::string name = (*it)[1];
    name.erase(0, name.find_first_not_of(' '));
    counts[name] = std::stol((*it)[2]);
  }
  return counts;
}

constexpr double kDuration = 60;  // s of sim time
// `modern`: 4 cameras at 80 Hz with phases of 0, 1, 2 and 1 steps of 1/240 s:
// in [0, 60] s camera 0 captures 4801 times, the others 4800 times each.
constexpr long kCaptureInstants = 4801 + 3 * 4800;

std::vector<std::string> fast_modern_run() {
  return {"--scenario", "division_a_11v11_planar", "--profile", "modern", "--speed", "0",
          "--duration", std::to_string(kDuration), "--demo",    "both"};
}

// Stops the vision for `pause` once it has published a few frames (mid-run).
void pause_vision_mid_run(Launch& launch, std::chrono::milliseconds pause) {
  VisionListener listener;
  const pid_t vision = launch.processes().at("vision");
  ASSERT_TRUE(listener.run_until([&] { return listener.frames().size() >= 100; }, 30))
      << launch.output();
  ASSERT_EQ(::kill(vision, SIGSTOP), 0);
  std::this_thread::sleep_for(pause);
  ASSERT_EQ(::kill(vision, SIGCONT), 0);
}

TEST(SpeedZero, AVisionStoppedForHalfASecondLosesNoFrame) {
  TempDir dir;
  Launch launch(fast_modern_run(), dir);
  pause_vision_mid_run(launch, std::chrono::milliseconds(500));
  ASSERT_EQ(launch.script().wait(60), 0) << launch.output();
  auto summary = vision_summary(dir);
  // Every capture instant of the run, the last ones included.
  EXPECT_EQ(summary["captured"], kCaptureInstants) << read_text(dir.path("logs/vision.log"));
  ASSERT_EQ(summary.count("frames lost"), 1u) << read_text(dir.path("logs/vision.log"));
  EXPECT_EQ(summary.at("frames lost"), 0);
  EXPECT_EQ(launch.output().find("lost"), std::string::npos) << launch.output();
  // Physics did wait for it (the half second, and whenever the vision fell behind).
  EXPECT_NE(read_text(dir.path("logs/physics.log")).find("for the vision emulator"),
            std::string::npos);
}

TEST(SpeedZero, FramesLostAnywayAreCountedAndShownOnTheTerminal) {
  // Stopped for longer than physics waits for a silent vision: physics runs
  // on, the vision's socket overflows, and the frames are lost, but not silently.
  TempDir dir;
  Launch launch(fast_modern_run(), dir);
  pause_vision_mid_run(launch, ubersim::kVisionSilence + std::chrono::milliseconds(300));
  ASSERT_EQ(launch.script().wait(60), 0) << launch.output();
  const auto summary = vision_summary(dir);
  ASSERT_EQ(summary.count("frames lost"), 1u) << read_text(dir.path("logs/vision.log"));
  EXPECT_GT(summary.at("frames lost"), 0);
  EXPECT_NE(launch.output().find("launch: vision lost " +
                                 std::to_string(summary.at("frames lost")) + " frames"),
            std::string::npos)
      << launch.output();
  EXPECT_NE(read_text(dir.path("logs/physics.log")).find("the vision emulator has said nothing"),
            std::string::npos);
}

}  // namespace
}  // namespace e2e
