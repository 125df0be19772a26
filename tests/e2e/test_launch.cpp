// End to end: the launch script, the demo team, the referee, the logger and
// lcm-logplayer as a user runs them, over real LCM multicast (this binary runs
// in its own network namespace: tests/run_isolated.sh).
#include <gtest/gtest.h>
#include <signal.h>

#include <cmath>
#include <regex>
#include <set>
#include <thread>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/sim_commands_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <ubersim/team_t.hpp>

#include "allowed_cpus.hpp"
#include "e2e_support.hpp"
#include "lockstep_replay.hpp"
#include "ubersim/common_options.hpp"

using namespace e2e;
using ubersim::test::allowed_cpus;
using ubersim::test::ChildProcess;
using ubersim::test::process_alive;

namespace {

constexpr double kVisionRate = 30.0;  // Hz, the cmdragons02 profile

const ubersim::vision_robot_t* find_robot(const ubersim::vision_frame_t& frame, bool yellow,
                                          int id) {
  for (const auto& r : yellow ? frame.robots_yellow : frame.robots_blue) {
    if (r.robot_id == id) return &r;
  }
  return nullptr;
}

// Runs a program to completion; returns its exit status and output.
std::pair<int, std::string> run(const std::vector<std::string>& argv, const TempDir& dir,
                                double timeout_s = 30) {
  static int counter = 0;
  ChildProcess process(argv, dir.path("run" + std::to_string(counter++) + ".out"));
  const int status = process.wait(timeout_s);
  return {status, process.log()};
}

}  // namespace

// One demo game, run once for the tests that look at it: 2 x 6 robots, both
// demo teams, at twice real time, recorded with ubersim_logger.
class DemoGame : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<TempDir>();
    listener_ = std::make_unique<VisionListener>();
    Launch launch({"--demo", "both", "--speed", "2", "--log", dir_->path("game.lcmlog")}, *dir_);
    pids_ = launch.processes();
    listener_->run_until(
        [] { return !listener_->frames().empty() && listener_->frames().back().t_capture >= 10.2; },
        90);
    const auto start = std::chrono::steady_clock::now();
    launch.script().stop(10, SIGINT);
    stop_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    launch_status_ = launch.script().wait(1);
    listener_->run_for(0.3);  // frames still in flight when it stopped
    output_ = launch.output();
  }
  static void TearDownTestSuite() {
    listener_.reset();
    dir_.reset();
  }

  static inline std::unique_ptr<TempDir> dir_;
  static inline std::unique_ptr<VisionListener> listener_;
  static inline std::map<std::string, pid_t> pids_;
  static inline double stop_seconds_ = 0;
  static inline int launch_status_ = -1;
  static inline std::string output_;
};

TEST_F(DemoGame, VisionArrivesAtTheConfiguredRate) {
  const auto& frames = listener_->frames();
  ASSERT_FALSE(frames.empty()) << output_;
  ASSERT_GE(frames.back().t_capture, 10.2) << "the game did not reach 10 s of sim time";
  // 9 s of capture time at 30 Hz: exactly 270 frames, numbered consecutively.
  int in_window = 0;
  for (const auto& f : frames) in_window += f.t_capture >= 0.99 && f.t_capture < 9.99;
  EXPECT_EQ(in_window, static_cast<int>(9 * kVisionRate));
  for (std::size_t i = 1; i < frames.size(); ++i) {
    EXPECT_EQ(frames[i].frame_number, frames[i - 1].frame_number + 1) << "at frame " << i;
  }
}

TEST_F(DemoGame, RobotsMove) {
  const auto& frames = listener_->frames();
  ASSERT_GT(frames.size(), 10u);
  const auto& first = frames.front();
  const auto& last = frames.back();
  int moved = 0;
  for (bool yellow : {true, false}) {
    for (int id = 0; id < 6; ++id) {
      const auto* a = find_robot(first, yellow, id);
      const auto* b = find_robot(last, yellow, id);
      if (a && b && std::hypot(a->x - b->x, a->y - b->y) > 0.3) ++moved;
    }
  }
  EXPECT_GE(moved, 4) << "robots that moved more than 0.3 m in 10 s";
}

TEST_F(DemoGame, SigintStopsEveryProcessWithinTwoSeconds) {
  // 130: stopped by Ctrl-C, as a shell reports it; 1 would mean a process failed.
  EXPECT_EQ(launch_status_, 130) << output_;
  EXPECT_NE(output_.find("launch: stopped (Ctrl-C)"), std::string::npos) << output_;
  // launch.sh kills (and reports) anything still running 2 s after it asked.
  EXPECT_EQ(output_.find("did not stop within 2 s"), std::string::npos) << output_;
  EXPECT_LT(stop_seconds_, 5.0);
  for (const char* name : {"physics", "vision", "radio", "demo_yellow", "demo_blue", "logger"}) {
    ASSERT_TRUE(pids_.count(name)) << name << " not started: " << output_;
    EXPECT_FALSE(process_alive(pids_.at(name))) << name << " left running";
  }
}

TEST_F(DemoGame, LogReplaysTheSameFrames) {
  VisionListener replayed;
  ChildProcess player({"/usr/bin/lcm-logplayer", "--speed=4", "--regexp=^VISION$",
                       "--lcm-url=" + ubersim::default_lcm_url(), dir_->path("game.lcmlog")},
                      dir_->path("logplayer.out"));
  replayed.run_until([&] { return !player.running(); }, 60);
  replayed.run_for(0.3);
  ASSERT_GT(listener_->bytes().size(), 250u);
  EXPECT_EQ(replayed.bytes().size(), listener_->bytes().size());
  EXPECT_TRUE(replayed.bytes() == listener_->bytes())
      << "replayed frames differ from the live ones";
}

TEST_F(DemoGame, RecordedCommandsReplayIdenticallyInLockstep) {
  const auto first = replay_in_lockstep(dir_->path("game.lcmlog"), 5.0, *dir_, "first");
  const auto second = replay_in_lockstep(dir_->path("game.lcmlog"), 5.0, *dir_, "second");
  EXPECT_GT(first.packets_replayed, 200);
  EXPECT_EQ(first.packets_not_forwarded, 0);
  EXPECT_EQ(second.packets_not_forwarded, 0);
  EXPECT_GE(first.frames.size(), static_cast<std::size_t>(4.5 * kVisionRate));
  EXPECT_EQ(first.frames.size(), second.frames.size());
  std::size_t same = 0;
  while (same < first.frames.size() && same < second.frames.size() &&
         first.frames[same] == second.frames[same]) {
    ++same;
  }
  EXPECT_TRUE(first.frames == second.frames)
      << "two lockstep replays gave different VISION from frame " << same;
}

TEST(Launch, KillingOneProcessStopsTheRestAndFails) {
  TempDir dir;
  VisionListener listener;
  Launch launch({}, dir);
  const auto pids = launch.processes();
  ASSERT_TRUE(listener.run_until([&] { return listener.frames().size() > 5; }, 30))
      << launch.output();
  // In real time physics, vision and radio share one CPU (docs/design.md, "One core in real time").
  const std::string cpu = allowed_cpus(pids.at("physics"));
  EXPECT_TRUE(std::regex_match(cpu, std::regex("[0-9]+"))) << cpu;
  EXPECT_EQ(allowed_cpus(pids.at("vision")), cpu);
  EXPECT_EQ(allowed_cpus(pids.at("radio")), cpu);
  ::kill(pids.at("radio"), SIGKILL);
  const int status = launch.script().wait(10);
  EXPECT_NE(status, 0) << launch.output();
  EXPECT_NE(launch.output().find("radio exited"), std::string::npos) << launch.output();
  for (const auto& [name, pid] : pids) EXPECT_FALSE(process_alive(pid)) << name << " left running";
}

TEST(Launch, CpuAllLeavesThePlacementToTheKernel) {
  TempDir dir;
  Launch launch({"--cpu", "all", "--no-vision", "--no-radio"}, dir);
  const auto pids = launch.processes();
  ASSERT_TRUE(pids.count("physics")) << launch.output();
  EXPECT_EQ(allowed_cpus(pids.at("physics")), allowed_cpus(::getpid()));
  // Stopped right after the start (the processes may not all be ready): none is left.
  launch.script().stop(10, SIGINT);
  for (const auto& [name, pid] : pids) EXPECT_FALSE(process_alive(pid)) << name << " left running";
}

// ER-Force's realism presets by their short names: both emulators run the
// erforce_ profile (four cameras, the preset's values).
TEST(Launch, ErForcePresetsByTheirShortNames) {
  TempDir dir;
  VisionListener listener;
  {
    Launch launch({"--profile", "rc2021"}, dir);
    launch.processes();
    std::set<int> cameras;
    ASSERT_TRUE(listener.run_until(
        [&] {
          for (const auto& f : listener.frames()) cameras.insert(f.camera_id);
          return cameras.size() == 4;
        },
        30))
        << launch.output();
    EXPECT_NE(launch.output().find("profile erforce_rc2021"), std::string::npos) << launch.output();
    EXPECT_EQ(launch.script().stop(10, SIGINT), 130) << launch.output();  // stopped by Ctrl-C
  }
  for (const char* name : {"none", "friendly", "realistic"}) {
    Launch launch({"--profile", name, "--no-vision", "--no-radio"}, dir);
    launch.processes();
    EXPECT_NE(launch.output().find(std::string("profile erforce_") + name), std::string::npos)
        << launch.output();
    launch.script().stop(10, SIGINT);
  }
}

TEST(Launch, RefereePlacementsShowInVision) {
  TempDir dir;
  VisionListener listener;
  Launch launch({}, dir);
  launch.processes();
  ASSERT_TRUE(listener.run_until([&] { return listener.frames().size() > 5; }, 30))
      << launch.output();
  const std::string referee = bin_dir() + "/ubersim_referee";
  const auto ball = run({referee, "place-ball", "1.0", "0.5"}, dir);
  ASSERT_EQ(ball.first, 0) << ball.second;
  const auto robot = run({referee, "place-robot", "yellow", "1", "-1.0", "1.0", "90"}, dir);
  ASSERT_EQ(robot.first, 0) << robot.second;
  std::smatch match;
  ASSERT_TRUE(std::regex_search(robot.second, match, std::regex(R"(sim time ([0-9.eE+-]+) s)")))
      << robot.second;
  const double placed_at = std::stod(match[1]);
  // Physics' dribbler mode, both ways, acknowledged.
  const auto perfect = run({referee, "dribbling", "perfect"}, dir);
  EXPECT_EQ(perfect.first, 0) << perfect.second;
  EXPECT_NE(perfect.second.find("perfect dribbling"), std::string::npos) << perfect.second;
  const auto simulated = run({referee, "dribbling", "simulated"}, dir);
  EXPECT_EQ(simulated.first, 0) << simulated.second;
  EXPECT_NE(simulated.second.find("simulated dribbling"), std::string::npos) << simulated.second;
  EXPECT_NE(run({referee, "dribbling", "sometimes"}, dir).first, 0);

  const std::size_t before = listener.frames().size();
  ASSERT_TRUE(listener.run_until(
      [&] {
        const auto& f = listener.frames();
        return f.size() > before && f.back().t_capture > placed_at + 0.2;
      },
      30));
  const auto& frame = listener.frames().back();
  ASSERT_FALSE(frame.balls.empty());
  EXPECT_NEAR(frame.balls[0].x, 1.0, 0.03);
  EXPECT_NEAR(frame.balls[0].y, 0.5, 0.03);
  const auto* r = find_robot(frame, true, 1);
  ASSERT_NE(r, nullptr);
  EXPECT_NEAR(r->x, -1.0, 0.03);
  EXPECT_NEAR(r->y, 1.0, 0.03);
  EXPECT_NEAR(r->orientation, M_PI / 2, 0.05);
  EXPECT_EQ(launch.script().stop(10, SIGINT), 130) << launch.output();  // stopped by Ctrl-C
}

TEST(Launch, RealVisionServerTakesTheEmulatorsPlace) {
  TempDir dir;
  VisionListener listener;
  std::vector<ubersim::sim_commands_t> forwarded;
  double sim_time = 0;
  listener.bus().subscribe<ubersim::sim_commands_t>(
      "SIM_COMMANDS", [&](const ubersim::sim_commands_t& c) { forwarded.push_back(c); });
  listener.bus().subscribe<ubersim::sim_state_t>(
      "SIM_STATE", [&](const ubersim::sim_state_t& s) { sim_time = s.sim_time; });
  Launch launch({"--no-vision"}, dir);
  const auto pids = launch.processes();
  EXPECT_EQ(pids.count("vision"), 0u);
  EXPECT_NE(launch.output().find("a real vision server must publish VISION"), std::string::npos);

  // The stand-in "real" vision server: camera 42, its own frame numbers.
  ubersim::MessageBus stand_in(ubersim::default_lcm_url());
  for (int i = 0; i < 60; ++i) {
    ubersim::vision_frame_t frame{};
    frame.camera_id = 42;
    frame.frame_number = 1000 + i;
    stand_in.publish("VISION", frame);
    // The radio path is untouched: a team's packet still reaches physics.
    ubersim::radio_packet_t packet{};
    packet.team = ubersim::team_t::YELLOW;
    packet.sequence = i;
    ubersim::robot_command_t command{};
    command.robot_id = 0;
    packet.commands.push_back(command);
    packet.num_commands = 1;
    stand_in.publish("RADIO_YELLOW", packet);
    listener.run_for(1.0 / kVisionRate);
  }
  listener.run_for(0.5);
  ASSERT_EQ(listener.frames().size(), 60u);
  for (const auto& f : listener.frames()) EXPECT_EQ(f.camera_id, 42);
  EXPECT_GT(sim_time, 1.0) << "physics kept running";
  EXPECT_GT(forwarded.size(), 30u) << "the radio emulator kept forwarding";
  EXPECT_EQ(launch.script().stop(10, SIGINT), 130) << launch.output();  // stopped by Ctrl-C
}
