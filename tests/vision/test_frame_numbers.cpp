// Frame numbers shared by the cameras of one capture instant (FRAME_NUMBERS =
// shared, the grsim profile), and the grsim profiles as grSim's cameras.
// Some SSL programs put a whole frame together from every camera's packet of
// one frame number, finishing it when a higher number arrives; the
// statistical test counts how many frames such a program finds complete.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <set>
#include <stdexcept>
#include <ubersim/team_t.hpp>

#include "ubersim/config.hpp"
#include "ubersim/vision/vision_emulator.hpp"

using ubersim::sim_state_t;
using ubersim::vision_frame_t;
using ubersim::vision::load_vision_profile;
using ubersim::vision::RobotSize;
using ubersim::vision::RobotSizes;
using ubersim::vision::VisionEmulator;
using ubersim::vision::VisionProfile;

namespace {

const std::string kConfigDir = UBERSIM_SOURCE_CONFIG_DIR;
constexpr double kDt = 1.0 / 240;

RobotSizes sizes() {
  return RobotSizes([](const std::string& type) -> RobotSize {
    if (type == "omni4_ssl") return RobotSize{0.09, 0.15, 0.07};
    throw std::runtime_error("no such robot type");
  });
}

// Twelve robots spread over a Division A field, moving, and a ball, at `step`.
sim_state_t world(std::int64_t step) {
  const double t = static_cast<double>(step) * kDt;
  sim_state_t s{};
  s.sim_time = t;
  s.step = step;
  s.dt = kDt;
  s.speed_factor = 1;
  s.ball_present = true;
  s.ball.position[0] = 4.0 * std::sin(0.3 * t);
  s.ball.position[1] = 3.0 * std::cos(0.2 * t);
  s.ball.position[2] = 0.0215;
  s.ball.orientation[0] = 1;
  for (int i = 0; i < 12; ++i) {
    ubersim::robot_state_t r{};
    r.team = i % 2 == 0 ? ubersim::team_t::YELLOW : ubersim::team_t::BLUE;
    r.robot_id = i / 2;
    r.robot_type = "omni4_ssl";
    r.x = 5.0 * std::cos(0.1 * t + i);
    r.y = 4.0 * std::sin(0.13 * t + 2 * i);
    r.orientation = std::remainder(0.5 * t + i, 2 * M_PI);
    r.body.orientation[0] = 1;
    s.robots.push_back(r);
  }
  s.num_robots = static_cast<std::int32_t>(s.robots.size());
  return s;
}

// The frames published over `seconds` of sim time; each SIM_STATE is lost
// with probability `loss` (a lost state is one the emulator never sees).
std::vector<vision_frame_t> run(const VisionProfile& profile, double seconds, double loss,
                                unsigned seed = 5) {
  VisionEmulator emulator(profile, sizes());
  std::mt19937 random(seed);
  std::bernoulli_distribution lost(loss);
  std::vector<vision_frame_t> frames;
  const auto steps = static_cast<std::int64_t>(seconds / kDt);
  for (std::int64_t step = 0; step < steps; ++step) {
    if (step > 0 && lost(random)) continue;
    for (auto& f : emulator.on_sim_state(world(step)).frames) frames.push_back(std::move(f));
  }
  return frames;
}

struct Assembly {
  int frames = 0;    // frame numbers finished
  int complete = 0;  // of them, with a packet of every camera
  double complete_fraction() const { return frames > 0 ? double(complete) / frames : 0; }
};

// As such a program does: the packets of the newest frame number are
// collected; a packet with a higher number finishes the frame; a packet with
// a lower one is late and dropped.
Assembly assemble_by_frame_number(const std::vector<vision_frame_t>& frames, int cameras) {
  Assembly result;
  std::int64_t current = -1;
  std::set<int> seen;
  for (const vision_frame_t& f : frames) {
    if (f.frame_number < current) continue;
    if (f.frame_number > current) {
      if (current >= 0) {
        ++result.frames;
        if (static_cast<int>(seen.size()) == cameras) ++result.complete;
      }
      current = f.frame_number;
      seen.clear();
    }
    seen.insert(f.camera_id);
  }
  return result;
}

}  // namespace

TEST(VisionGrsimProfile, FourCamerasAsGrSimPlacesAndNumbersThem) {
  const VisionProfile p = load_vision_profile(kConfigDir, "grsim");
  ASSERT_EQ(p.cameras.size(), 4u);
  EXPECT_TRUE(p.shared_frame_numbers);
  EXPECT_DOUBLE_EQ(p.latency, 0);
  EXPECT_DOUBLE_EQ(p.processing_time, 0);
  EXPECT_DOUBLE_EQ(p.robot_sigma_x, 0);
  EXPECT_DOUBLE_EQ(p.robot_detection_probability, 1);
  EXPECT_DOUBLE_EQ(p.camera_overlap, 0.2);
  // grSim's cameraPosition(): 0 (+,+), 1 (+,-), 2 (-,-), 3 (-,+) at (L/4, W/4), 4 m up.
  const double x[] = {3.0, 3.0, -3.0, -3.0};
  const double y[] = {2.25, -2.25, -2.25, 2.25};
  for (int i = 0; i < 4; ++i) {
    const auto& c = p.cameras[static_cast<std::size_t>(i)];
    EXPECT_EQ(c.id, i);
    EXPECT_DOUBLE_EQ(c.frame_rate, 60);
    EXPECT_DOUBLE_EQ(c.phase, 0);
    EXPECT_DOUBLE_EQ(c.position.x(), x[i]);
    EXPECT_DOUBLE_EQ(c.position.y(), y[i]);
    EXPECT_DOUBLE_EQ(c.position.z(), 4.0);
  }
  const VisionProfile b = load_vision_profile(kConfigDir, "grsim_div_b");
  ASSERT_EQ(b.cameras.size(), 4u);
  EXPECT_TRUE(b.shared_frame_numbers);
  EXPECT_DOUBLE_EQ(b.cameras[1].position.x(), 2.25);
  EXPECT_DOUBLE_EQ(b.cameras[1].position.y(), -1.5);
}

TEST(VisionFrameNumbers, UnknownNumberingIsAnErrorNamingTheKey) {
  const std::string text = "BASE = " + kConfigDir + "/vision/grsim.cfg\nFRAME_NUMBERS = global\n";
  try {
    load_vision_profile(ubersim::ConfigFile::parse(text, "bad.cfg"), "bad");
    FAIL() << "FRAME_NUMBERS = global loaded";
  } catch (const ubersim::ConfigError& error) {
    EXPECT_NE(std::string(error.what()).find("FRAME_NUMBERS"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("per_camera or shared"), std::string::npos)
        << error.what();
  }
}

// Every frame number of the grsim profile holds one frame of each camera,
// captured at one instant, numbers rising by one per 60 Hz instant.
TEST(VisionFrameNumbers, SharedNumbersMarkOneInstantOfEveryCamera) {
  const auto frames = run(load_vision_profile(kConfigDir, "grsim"), 5.0, 0.0);
  std::map<std::int64_t, std::set<int>> cameras_of;
  std::map<std::int64_t, std::set<double>> instants_of;
  for (const vision_frame_t& f : frames) {
    cameras_of[f.frame_number].insert(f.camera_id);
    instants_of[f.frame_number].insert(f.t_capture);
  }
  ASSERT_GE(cameras_of.size(), 299u);  // 60 Hz x 5 s
  std::int64_t expected = cameras_of.begin()->first;
  for (const auto& [number, cameras] : cameras_of) {
    EXPECT_EQ(number, expected++);
    EXPECT_EQ(cameras.size(), 4u) << "frame " << number;
    EXPECT_EQ(instants_of[number].size(), 1u) << "frame " << number;
  }
}

// Statistical: with 10 % of SIM_STATE messages lost, a program assembling
// frames by number finds every grsim frame complete (lost instants skip
// numbers for all cameras alike); with the four unsynchronised cameras of
// `modern`, numbered per camera, it finds many incomplete.
TEST(VisionFrameNumbers, AssembledByNumberEveryGrsimFrameIsComplete) {
  const auto grsim =
      assemble_by_frame_number(run(load_vision_profile(kConfigDir, "grsim"), 20.0, 0.1), 4);
  const auto modern =
      assemble_by_frame_number(run(load_vision_profile(kConfigDir, "modern"), 20.0, 0.1), 4);
  std::printf(
      "frames complete when assembled by frame number: grsim %d of %d (%.1f %%), modern "
      "%d of %d (%.1f %%)\n",
      grsim.complete, grsim.frames, 100 * grsim.complete_fraction(), modern.complete, modern.frames,
      100 * modern.complete_fraction());
  EXPECT_GT(grsim.frames, 1000);  // 60 Hz x 20 s, less the instants lost with their state
  EXPECT_EQ(grsim.complete, grsim.frames);
  EXPECT_GT(modern.frames, 1000);
  EXPECT_LT(modern.complete_fraction(), 0.99);
}

// Cameras of different rates share a number only when they capture at one
// step; missed instants skip numbers as they do for a camera alone.
TEST(VisionFrameNumbers, SharedNumbersCountInstantsOfAnyCamera) {
  VisionProfile p = load_vision_profile(kConfigDir, "grsim");
  p.cameras.resize(2);
  p.cameras[1].frame_rate = 30;
  const auto frames = run(p, 1.0, 0.0);
  std::map<std::int64_t, std::set<int>> cameras_of;
  std::map<std::int64_t, std::set<double>> instants_of;
  for (const vision_frame_t& f : frames) {
    cameras_of[f.frame_number].insert(f.camera_id);
    instants_of[f.frame_number].insert(f.t_capture);
  }
  ASSERT_GE(cameras_of.size(), 59u);
  for (const auto& [number, instants] : instants_of) {
    EXPECT_EQ(instants.size(), 1u) << "frame " << number << " holds captures of two instants";
  }
  int both = 0;
  for (const auto& [number, cameras] : cameras_of) {
    if (cameras.size() == 2) ++both;
    EXPECT_TRUE(cameras.count(0)) << "camera 0 captures at every instant; frame " << number;
  }
  EXPECT_NEAR(both, static_cast<int>(cameras_of.size()) / 2, 1);
  EXPECT_EQ(cameras_of.rbegin()->first - cameras_of.begin()->first + 1,
            static_cast<std::int64_t>(cameras_of.size()));
}
