// The emulator core in one process: determinism, latency bookkeeping, reset,
// skipped states and the geometry message.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <ubersim/team_t.hpp>

#include "ubersim/config.hpp"
#include "ubersim/vision/vision_emulator.hpp"

using ubersim::ConfigFile;
using ubersim::field_geometry_t;
using ubersim::sim_state_t;
using ubersim::vision_frame_t;
using ubersim::vision::RobotSize;
using ubersim::vision::RobotSizes;
using ubersim::vision::VisionEmulator;
using ubersim::vision::VisionProfile;
using Verdict = ubersim::vision::VisionEmulator::Verdict;

namespace {

constexpr double kDt = 1.0 / 240;

std::string profile_text(const std::string& extra = "") {
  return R"(SEED = 11
FRAME_RATE = 60
LATENCY = 0.05
LATENCY_JITTER = 0.004
PROCESSING_TIME = 0.01
GEOMETRY_PERIOD = 1
ROBOT_SIGMA_X = 0.01
ROBOT_SIGMA_Y = 0.01
ROBOT_SIGMA_ORIENTATION = 0.05
BALL_SIGMA_X = 0.01
BALL_SIGMA_Y = 0.01
ROBOT_DETECTION_PROBABILITY = 0.9
BALL_DETECTION_PROBABILITY = 0.9
ROBOT_CONFIDENCE = 0.8
BALL_CONFIDENCE = 0.8
CONFIDENCE_SIGMA = 0.1
FALSE_BALL_RATE = 2
FALSE_BALL_SPREAD = 0.02
FALSE_BALL_CONFIDENCE = 0.3
BALL_MIN_VISIBLE_FRACTION = 0.3
BALL_RADIUS = 0.0215
CAMERA_COUNT = 2
CAMERA_0_POSITION = -1 0 4
CAMERA_0_ORIENTATION_DEG = 0 0 0
CAMERA_0_FOCAL_LENGTH = 300
CAMERA_0_IMAGE_SIZE = 640 480
CAMERA_0_PHASE = 0
CAMERA_1_POSITION = 1 0 4
CAMERA_1_ORIENTATION_DEG = 0 0 0
CAMERA_1_FOCAL_LENGTH = 300
CAMERA_1_IMAGE_SIZE = 640 480
CAMERA_1_PHASE = 0.0041667
)" + extra;
}

VisionProfile profile(const std::string& extra = "") {
  return ubersim::vision::load_vision_profile(ConfigFile::parse(profile_text(extra), "core.cfg"),
                                              "core");
}

RobotSizes sizes() {
  return RobotSizes([](const std::string& type) -> RobotSize {
    if (type == "small") return RobotSize{0.08, 0.12, 0.06};
    throw std::runtime_error("no such robot type");
  });
}

// Six robots circling and a ball rolling, at step `step`.
sim_state_t world(std::int64_t step) {
  const double t = static_cast<double>(step) * kDt;
  sim_state_t s{};
  s.sim_time = t;
  s.step = step;
  s.dt = kDt;
  s.speed_factor = 1;
  s.ball_present = true;
  s.ball.position[0] = -1.5 + 0.3 * t;
  s.ball.position[1] = 0.2;
  s.ball.position[2] = 0.0215;
  s.ball.orientation[0] = 1;
  for (int i = 0; i < 6; ++i) {
    ubersim::robot_state_t r{};
    r.team = i % 2 == 0 ? ubersim::team_t::YELLOW : ubersim::team_t::BLUE;
    r.robot_id = i;
    r.robot_type = "small";
    r.x = 0.8 * std::cos(0.5 * t + i);
    r.y = 0.8 * std::sin(0.5 * t + i);
    r.orientation = std::remainder(0.5 * t + i, 2 * M_PI);
    r.body.orientation[0] = 1;
    s.robots.push_back(r);
  }
  s.num_robots = static_cast<std::int32_t>(s.robots.size());
  return s;
}

std::vector<std::vector<char>> encode_all(const std::vector<vision_frame_t>& frames) {
  std::vector<std::vector<char>> out;
  for (const auto& f : frames) {
    std::vector<char> bytes(static_cast<std::size_t>(f.getEncodedSize()));
    f.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    out.push_back(std::move(bytes));
  }
  return out;
}

std::vector<vision_frame_t> run(VisionEmulator& emulator, std::int64_t first, std::int64_t last) {
  std::vector<vision_frame_t> frames;
  for (std::int64_t step = first; step <= last; ++step) {
    auto outcome = emulator.on_sim_state(world(step));
    for (auto& f : outcome.frames) frames.push_back(std::move(f));
  }
  return frames;
}

}  // namespace

TEST(VisionEmulatorCore, SameSeedSameFramesOtherSeedOtherFrames) {
  VisionEmulator a(profile(), sizes());
  VisionEmulator b(profile(), sizes());
  VisionProfile reseeded = profile();
  reseeded.seed = 12;
  VisionEmulator c(reseeded, sizes());
  const auto frames_a = encode_all(run(a, 0, 1199));
  const auto frames_b = encode_all(run(b, 0, 1199));
  const auto frames_c = encode_all(run(c, 0, 1199));
  ASSERT_GT(frames_a.size(), 550u);  // 2 cameras x 60 Hz x 5 s, less the latency tail
  EXPECT_EQ(frames_a, frames_b);
  EXPECT_NE(frames_a, frames_c);
}

TEST(VisionEmulatorCore, FramesLeaveAtTheFirstStepAfterTheirLatency) {
  VisionEmulator emulator(profile("CAMERA_1_LATENCY_JITTER = 0\n"), sizes());
  int checked = 0;
  for (std::int64_t step = 0; step < 480; ++step) {
    const auto outcome = emulator.on_sim_state(world(step));
    const double now = static_cast<double>(step) * kDt;
    for (const auto& f : outcome.frames) {
      EXPECT_NEAR(f.t_sent - f.t_capture, 0.01, 1e-12);
      if (f.camera_id != 1) continue;
      // 0.05 s is 12 steps exactly: published at that very step.
      EXPECT_NEAR(now - f.t_capture, 0.05, 1e-9);
      ++checked;
    }
  }
  EXPECT_GT(checked, 100);
}

// As the vision process uses it: one demand at the first state, the next at
// the first state at or after demand_renewal_time(). Physics publishes states
// only at what was demanded, so every frame's publication instant must have
// been announced before the step that publishes it, while a demand goes out
// only every few frames (each wakes physics).
TEST(VisionEmulatorCore, EachDemandCoversTheFramesUntilTheNext) {
  VisionEmulator emulator(profile(), sizes());
  std::vector<double> announced;
  double renewal = 0;
  int demands = 0;
  int frames = 0;
  for (std::int64_t step = 0; step < 960; ++step) {
    const double now = static_cast<double>(step) * kDt;
    for (const auto& f : emulator.on_sim_state(world(step)).frames) {
      ++frames;
      // Published at the first step at or after an announced instant.
      const bool covered = std::any_of(announced.begin(), announced.end(), [&](double t) {
        return t <= now + 1e-6 && t > now - kDt + 1e-6;
      });
      EXPECT_TRUE(covered) << "frame " << f.frame_number << " of camera " << f.camera_id
                           << " published at " << now << " s was not demanded";
    }
    if (now >= renewal - 1e-6) {
      const ubersim::truth_demand_t demand = emulator.truth_demand();
      ++demands;
      EXPECT_EQ(demand.num_periodic, 2);
      for (double t : demand.instants) {
        EXPECT_GT(t, now);  // only what is still to come
        announced.push_back(t);
      }
      renewal = emulator.demand_renewal_time();
      EXPECT_GT(renewal, now);
    }
  }
  EXPECT_GT(frames, 400);  // 2 cameras x 60 Hz x 4 s, less the latency tail
  // Renewed every kFramesAhead - 2 = 6 frames of a camera (its phase apart from the other's).
  EXPECT_LE(demands, 4 * 60 / 6 + 2);
  EXPECT_GE(demands, 4 * 60 / 8);
}

TEST(VisionEmulatorCore, ResetDropsPendingFramesAndKeepsNumbersIncreasing) {
  VisionEmulator emulator(profile(), sizes());
  const auto before = run(emulator, 0, 299);
  ASSERT_FALSE(before.empty());
  std::int64_t last_number = -1;
  for (const auto& f : before) {
    if (f.camera_id == 0) last_number = f.frame_number;
  }
  const auto reset = emulator.on_sim_state(world(0));
  EXPECT_EQ(reset.verdict, Verdict::Reset);
  EXPECT_TRUE(reset.frames.empty());  // the world they showed is gone
  EXPECT_EQ(emulator.stats().resets, 1u);
  EXPECT_GT(emulator.stats().frames_dropped_at_reset, 0u);
  EXPECT_DOUBLE_EQ(emulator.sim_time(), 0.0);

  const auto after = run(emulator, 1, 120);
  ASSERT_FALSE(after.empty());
  std::int64_t previous = last_number;
  bool first = true;
  for (const auto& f : after) {
    EXPECT_LT(f.t_capture, 0.5 + 1e-9);  // captured in the new timeline
    if (f.camera_id != 0) continue;
    EXPECT_GT(f.frame_number, previous);
    if (first) {
      EXPECT_DOUBLE_EQ(f.t_capture, 0.0);  // the phase restarts at the reset
    }
    first = false;
    previous = f.frame_number;
  }
}

TEST(VisionEmulatorCore, BadOldAndRepeatedStatesAreSkipped) {
  VisionEmulator emulator(profile(), sizes());
  run(emulator, 0, 100);
  sim_state_t bad = world(101);
  bad.robots[3].x = std::nan("");
  EXPECT_EQ(emulator.on_sim_state(bad).verdict, Verdict::Invalid);
  bad = world(101);
  bad.robots[0].team = 7;
  EXPECT_EQ(emulator.on_sim_state(bad).verdict, Verdict::Invalid);
  bad = world(101);
  bad.dt = 0;
  EXPECT_EQ(emulator.on_sim_state(bad).verdict, Verdict::Invalid);
  bad = world(101);
  bad.ball.position[2] = INFINITY;
  EXPECT_EQ(emulator.on_sim_state(bad).verdict, Verdict::Invalid);
  bad = world(101);
  bad.num_robots = 9;  // a local message can disagree with itself
  EXPECT_EQ(emulator.on_sim_state(bad).verdict, Verdict::Invalid);
  EXPECT_EQ(emulator.on_sim_state(world(50)).verdict, Verdict::OutOfOrder);
  // Finite but beyond any run (fuzz finding 12): its capture instant would not fit a 64-bit count.
  bad = world(101);
  bad.sim_time = 1.6e39;
  EXPECT_EQ(emulator.on_sim_state(bad).verdict, Verdict::OutOfOrder);
  EXPECT_EQ(emulator.on_sim_state(world(100)).verdict, Verdict::Repeated);
  EXPECT_EQ(emulator.stats().states_invalid, 5u);
  EXPECT_EQ(emulator.stats().states_out_of_order, 2u);
  EXPECT_EQ(emulator.stats().states_repeated, 1u);
  EXPECT_DOUBLE_EQ(emulator.sim_time(), 100 * kDt);
  // And on it goes, with nothing non-finite in any frame.
  for (const auto& f : run(emulator, 101, 400)) {
    for (const auto& r : f.robots_yellow) EXPECT_TRUE(std::isfinite(r.x + r.y + r.orientation));
    for (const auto& b : f.balls) EXPECT_TRUE(std::isfinite(b.x + b.y + b.pixel_x + b.pixel_y));
  }
}

TEST(VisionEmulatorCore, GeometryCarriesTheBelievedCalibrationAndTheField) {
  VisionEmulator emulator(profile("CAMERA_1_CALIBRATION_ERROR_POSITION = 0.02 -0.01 0.05\n"),
                          sizes());
  auto message = emulator.geometry_message();
  EXPECT_EQ(message.field.name, "");  // not known yet
  ASSERT_EQ(message.num_cameras, 2);
  EXPECT_DOUBLE_EQ(message.cameras[0].position[0], -1.0);
  EXPECT_DOUBLE_EQ(message.cameras[1].position[0], 1.02);
  EXPECT_DOUBLE_EQ(message.cameras[1].position[1], -0.01);
  EXPECT_DOUBLE_EQ(message.cameras[1].position[2], 4.05);

  field_geometry_t field{};
  field.name = "division_b";
  field.field_length = 9;
  field.field_width = 6;
  field.ball_radius = 0.0215;
  EXPECT_TRUE(emulator.on_field_geometry(field));
  EXPECT_FALSE(emulator.on_field_geometry(field));  // nothing new
  field_geometry_t broken = field;
  broken.ball_radius = std::nan("");
  EXPECT_FALSE(emulator.on_field_geometry(broken));
  EXPECT_EQ(emulator.stats().geometry_invalid, 1u);
  message = emulator.geometry_message();
  EXPECT_EQ(message.field.name, "division_b");
  EXPECT_DOUBLE_EQ(message.field.field_length, 9);
}

TEST(VisionEmulatorCore, UnknownRobotTypeIsSeenAsAnSslRobot) {
  VisionProfile p = profile();
  p.robot_sigma_x = p.robot_sigma_y = p.robot_sigma_orientation = 0;
  p.robot_detection_probability = 1;
  VisionEmulator emulator(p, sizes());
  sim_state_t s = world(0);
  s.robots.resize(1);
  s.num_robots = 1;
  s.robots[0].robot_type = "no_such_type";
  s.robots[0].x = -1.2;
  s.robots[0].y = 0.3;
  VisionEmulator::Output outcome = emulator.on_sim_state(s);
  std::vector<vision_frame_t> frames;
  for (std::int64_t step = 1; step < 30; ++step) {
    sim_state_t next = s;
    next.step = step;
    next.sim_time = static_cast<double>(step) * kDt;
    for (auto& f : emulator.on_sim_state(next).frames) frames.push_back(f);
  }
  ASSERT_FALSE(frames.empty());
  ASSERT_EQ(frames[0].num_robots_yellow, 1);
  EXPECT_NEAR(frames[0].robots_yellow[0].x, -1.2, 1e-9);
  EXPECT_NEAR(frames[0].robots_yellow[0].y, 0.3, 1e-9);
}
