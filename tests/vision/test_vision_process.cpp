// The tests of the vision emulator, end to end: the real
// ubersim_vision process, driven over real LCM multicast by a stand-in for
// physics that publishes synthetic ground truth at 240 Hz of sim time (see
// vision_test_support.hpp for the lockstep that makes timing exact).
// Expected values come from the test's own geometry, not the emulator's code.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <numeric>
#include <set>
#include <thread>
#include <ubersim/team_t.hpp>
#include <ubersim/truth_demand_t.hpp>
#include <ubersim/vision_schedule_t.hpp>

#include "ubersim/angles.hpp"
#include "ubersim/common_options.hpp"
#include "ubersim/config.hpp"
#include "ubersim/robot_config.hpp"
#include "ubersim/topics.hpp"
#include "ubersim/vision_backpressure.hpp"
#include "vision_test_support.hpp"

using namespace vision_test;
using Eigen::Vector2d;
using Eigen::Vector3d;
using ubersim::vision_frame_t;

namespace {

constexpr double kBallRadius = 0.0215;

// Profile values every test starts from: one straight-down camera 4 m above
// (0.5, -0.3) seeing 12.8 m x 9.6 m, no noise, no dropouts, 60 Hz.
std::map<std::string, std::string> base_keys() {
  return {{"SEED", "3"},
          {"FRAME_RATE", "60"},
          {"LATENCY", "0.05"},
          {"LATENCY_JITTER", "0"},
          {"PROCESSING_TIME", "0.01"},
          {"GEOMETRY_PERIOD", "1"},
          {"ROBOT_SIGMA_X", "0"},
          {"ROBOT_SIGMA_Y", "0"},
          {"ROBOT_SIGMA_ORIENTATION", "0"},
          {"BALL_SIGMA_X", "0"},
          {"BALL_SIGMA_Y", "0"},
          {"ROBOT_DETECTION_PROBABILITY", "1"},
          {"BALL_DETECTION_PROBABILITY", "1"},
          {"ROBOT_CONFIDENCE", "0.9"},
          {"BALL_CONFIDENCE", "0.9"},
          {"CONFIDENCE_SIGMA", "0"},
          {"FALSE_BALL_RATE", "0"},
          {"FALSE_BALL_SPREAD", "0.01"},
          {"FALSE_BALL_CONFIDENCE", "0.3"},
          {"BALL_MIN_VISIBLE_FRACTION", "0.5"},
          {"BALL_RADIUS", "0.0215"},
          {"CAMERA_0_POSITION", "0.5 -0.3 4.0"},
          {"CAMERA_0_ORIENTATION_DEG", "0 0 0"},
          {"CAMERA_0_FOCAL_LENGTH", "400"},
          {"CAMERA_0_IMAGE_SIZE", "1280 960"},
          {"CAMERA_0_PHASE", "0"}};
}

// A profile of `cameras` cameras plus the lockstep marker camera (id = cameras).
std::string profile_text(std::map<std::string, std::string> keys, int cameras = 1) {
  keys["CAMERA_COUNT"] = std::to_string(cameras + 1);
  std::string text;
  for (const auto& [key, value] : keys) text.append(key).append(" = ").append(value).append("\n");
  return text + marker_camera_keys(cameras);
}

// A straight-down camera as the test understands it (no library code).
struct DownCamera {
  Vector3d position;
  double focal = 400, cx = 640, cy = 480;
  Vector2d pixel(const Vector3d& p) const {
    const double depth = position.z() - p.z();
    return {cx + focal * (p.x() - position.x()) / depth,
            cy - focal * (p.y() - position.y()) / depth};
  }
};
const DownCamera kCamera{Vector3d(0.5, -0.3, 4.0)};

const ubersim::RobotTypeConfig& omni4() {
  static const ubersim::RobotTypeConfig robot =
      ubersim::load_robot_config(config_dir(), "omni4_ssl");
  return robot;
}

// Ten robots of both teams circling at different radii and speeds; one keeps
// a heading just short of pi so that noise wraps it.
Truth moving_robots(double t, bool ball) {
  Truth truth;
  for (int i = 0; i < 10; ++i) {
    TruthRobot r;
    r.team = i < 5 ? ubersim::team_t::YELLOW : ubersim::team_t::BLUE;
    r.id = i % 5;
    const double radius = 0.6 + 0.25 * i;
    const double angle = 0.3 * (i % 3 + 1) * t + i;
    r.x = radius * std::cos(angle);
    r.y = -0.5 + 0.6 * radius * std::sin(angle);
    r.orientation = i == 0 ? M_PI - 0.01 : ubersim::wrap_angle(angle + M_PI / 2);
    truth.robots.push_back(r);
  }
  truth.ball_present = ball;
  truth.ball = Vector3d(-2.0 + 0.4 * t, 3.0, kBallRadius);  // clear of the robots
  return truth;
}

struct Stats {
  double mean = 0, sd = 0;
  std::size_t n = 0;
};
Stats stats_of(const std::vector<double>& v) {
  Stats s;
  s.n = v.size();
  s.mean = std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(s.n);
  double sum = 0;
  for (double x : v) sum += (x - s.mean) * (x - s.mean);
  s.sd = std::sqrt(sum / static_cast<double>(s.n - 1));
  return s;
}

// Sample sd within 10 % of sigma (about 3 standard errors of an sd for the
// smallest sample used, n = 3000: se = sigma / sqrt(2 n) = 1.3 %), and the
// mean within 3 standard errors of zero.
void expect_gaussian(const std::vector<double>& errors, double sigma, const char* what) {
  ASSERT_GE(errors.size(), 3000u) << what;
  const Stats s = stats_of(errors);
  EXPECT_NEAR(s.sd, sigma, 0.1 * sigma) << what;
  EXPECT_LT(std::abs(s.mean), 3 * s.sd / std::sqrt(static_cast<double>(s.n))) << what;
}

const vision_frame_t& frame_of(const Received& r) {
  return r.frame;
}

std::vector<const ubersim::vision_robot_t*> robots_in(const vision_frame_t& f, std::int8_t team) {
  std::vector<const ubersim::vision_robot_t*> out;
  for (const auto& r : team == ubersim::team_t::YELLOW ? f.robots_yellow : f.robots_blue) {
    out.push_back(&r);
  }
  return out;
}

const TruthRobot* truth_robot(const Truth& truth, std::int8_t team, int id) {
  for (const auto& r : truth.robots) {
    if (r.team == team && r.id == id) return &r;
  }
  return nullptr;
}

class VisionProcess : public ::testing::Test {
 protected:
  // Starts ubersim_vision and waits until it listens (it asks for the geometry).
  void start(const std::string& profile, std::vector<std::string> extra = {}) {
    std::vector<std::string> argv{vision_program(), "--profile", profile, "--config-dir",
                                  config_dir()};
    argv.insert(argv.end(), extra.begin(), extra.end());
    driver = std::make_unique<SimDriver>();  // listening before the child can speak
    log = dir.path("vision_" + std::to_string(++runs) + ".log");
    emulator = std::make_unique<ChildProcess>(argv, log);
    ASSERT_TRUE(driver->wait_for_emulator(division_b_geometry())) << driver->failure() << "\n"
                                                                  << read_text(log);
  }
  std::string profile(const std::map<std::string, std::string>& keys, int cameras = 1) {
    return dir.write("profile_" + std::to_string(runs + 1) + ".cfg", profile_text(keys, cameras));
  }
  // Stops the emulator: it must exit 0 on SIGTERM.
  void stop() {
    ASSERT_TRUE(emulator);
    EXPECT_EQ(emulator->stop(), 0) << read_text(log);
  }
  void lockstep(std::int64_t first, std::int64_t last, const World& world, int marker = 1) {
    ASSERT_TRUE(driver->run_lockstep(first, last, world, marker)) << driver->failure() << "\n"
                                                                  << read_text(log);
  }

  TempDir dir;
  std::unique_ptr<SimDriver> driver;
  std::unique_ptr<ChildProcess> emulator;
  std::string log;
  int runs = 0;
};

}  // namespace

// Rate: the paper's profile as shipped, 10 s of sim time at 30 Hz.
TEST_F(VisionProcess, RateIsExactly300FramesIn10SimSecondsNumberedConsecutively) {
  start("cmdragons02");
  const World world = [](double t) { return moving_robots(t, true); };
  ASSERT_TRUE(driver->run_windowed(0, 2400 + 48, world, 0.3, 1)) << driver->failure();
  driver->listen(0.3);
  stop();
  const auto frames = driver->frames(0);
  std::vector<const vision_frame_t*> in_ten_seconds;
  for (const auto& r : frames) {
    if (r.frame.t_capture < 10.0 - 1e-9) in_ten_seconds.push_back(&r.frame);
  }
  ASSERT_EQ(in_ten_seconds.size(), 300u);
  for (std::size_t n = 0; n < in_ten_seconds.size(); ++n) {
    EXPECT_EQ(in_ten_seconds[n]->frame_number, static_cast<std::int64_t>(n));
    EXPECT_NEAR(in_ten_seconds[n]->t_capture, static_cast<double>(n) / 30, 1e-9);  // phase-locked
  }
  EXPECT_EQ(exit_summary(read_text(log))["invalid"], 0);
}

// Latency: publication time minus capture time, measured in sim time.
TEST_F(VisionProcess, LatencyMeanIsTheConfiguredLatencyAndSpreadTheJitter) {
  auto keys = base_keys();
  keys["LATENCY_JITTER"] = "0.003";
  keys["PROCESSING_TIME"] = "0.012";
  // A second camera with a fixed latency that is not a whole number of steps.
  keys["CAMERA_1_POSITION"] = "0.5 -0.3 4.0";
  keys["CAMERA_1_ORIENTATION_DEG"] = "0 0 0";
  keys["CAMERA_1_FOCAL_LENGTH"] = "400";
  keys["CAMERA_1_IMAGE_SIZE"] = "1280 960";
  keys["CAMERA_1_PHASE"] = "0.0083333";
  keys["CAMERA_1_LATENCY"] = "0.03";
  keys["CAMERA_1_LATENCY_JITTER"] = "0";
  keys["CAMERA_1_PROCESSING_TIME"] = "0.005";
  start(profile(keys, 2));
  lockstep(
      0, 2400, [](double t) { return moving_robots(t, true); }, 2);
  stop();

  std::vector<double> delays;
  std::int64_t previous_step = -1, previous_number = -1;
  for (const auto& r : driver->frames(0)) {
    ASSERT_GE(r.published_at_step, 0);
    delays.push_back(static_cast<double>(r.published_at_step) * kDt - r.frame.t_capture);
    EXPECT_NEAR(r.frame.t_sent - r.frame.t_capture, 0.012, 1e-9);
    EXPECT_GE(r.published_at_step, previous_step);  // never out of order
    EXPECT_EQ(r.frame.frame_number, previous_number + 1);
    previous_step = r.published_at_step;
    previous_number = r.frame.frame_number;
  }
  ASSERT_GE(delays.size(), 590u);
  const Stats s = stats_of(delays);
  // The criterion: the mean within one physics step of the latency.
  EXPECT_NEAR(s.mean, 0.05, kDt);
  // Sharper: a frame leaves at the first step at or after t + latency, which
  // adds a uniform [0, dt) wait: mean latency + dt / 2, variance jitter^2 + dt^2 / 12.
  const double expected_sd = std::sqrt(0.003 * 0.003 + kDt * kDt / 12);
  EXPECT_NEAR(s.mean, 0.05 + kDt / 2, 3 * expected_sd / std::sqrt(static_cast<double>(s.n)));
  // n = 600: the sd's standard error is 2.9 %; 10 % is 3.4 of them.
  EXPECT_NEAR(s.sd, expected_sd, 0.1 * expected_sd);

  const auto fixed = driver->frames(1);
  ASSERT_GE(fixed.size(), 590u);
  for (const auto& r : fixed) {
    // 30 ms is 7.2 steps: every frame leaves at the 8th step after its capture.
    EXPECT_NEAR(static_cast<double>(r.published_at_step) * kDt - r.frame.t_capture, 8 * kDt, 1e-9);
    EXPECT_NEAR(r.frame.t_sent - r.frame.t_capture, 0.005, 1e-9);
  }
}

// Noise: detected minus true, over thousands of detections of moving objects.
TEST_F(VisionProcess, NoiseHasTheConfiguredSigmasAndNoBias) {
  auto keys = base_keys();
  keys["FRAME_RATE"] = "240";  // one frame per step: 3000 ball detections in 12.5 s
  keys["LATENCY"] = "0.02";
  keys["ROBOT_SIGMA_X"] = "0.01";
  keys["ROBOT_SIGMA_Y"] = "0.02";
  keys["ROBOT_SIGMA_ORIENTATION"] = "0.05";
  keys["BALL_SIGMA_X"] = "0.015";
  keys["BALL_SIGMA_Y"] = "0.008";
  start(profile(keys));
  const World world = [](double t) { return moving_robots(t, true); };
  lockstep(0, 3005, world);
  stop();

  std::vector<double> rx, ry, rtheta, bx, by;
  for (const auto& r : driver->frames(0)) {
    const vision_frame_t& f = frame_of(r);
    const Truth truth = world(f.t_capture);
    for (std::int8_t team : {ubersim::team_t::YELLOW, ubersim::team_t::BLUE}) {
      for (const auto* d : robots_in(f, team)) {
        const TruthRobot* t = truth_robot(truth, team, d->robot_id);
        ASSERT_NE(t, nullptr);
        rx.push_back(d->x - t->x);
        ry.push_back(d->y - t->y);
        ASSERT_GT(d->orientation, -M_PI);
        ASSERT_LE(d->orientation, M_PI);
        rtheta.push_back(ubersim::wrap_angle(d->orientation - t->orientation));
      }
    }
    ASSERT_EQ(f.num_balls, 1);
    bx.push_back(f.balls[0].x - truth.ball.x());
    by.push_back(f.balls[0].y - truth.ball.y());
  }
  expect_gaussian(rx, 0.01, "robot x");
  expect_gaussian(ry, 0.02, "robot y");
  expect_gaussian(rtheta, 0.05, "robot orientation");
  expect_gaussian(bx, 0.015, "ball x");
  expect_gaussian(by, 0.008, "ball y");
}

// Dropouts and confidence.
TEST_F(VisionProcess, DetectionRatesMatchTheConfiguredProbabilities) {
  auto keys = base_keys();
  keys["FRAME_RATE"] = "240";
  keys["ROBOT_DETECTION_PROBABILITY"] = "0.8";
  keys["BALL_DETECTION_PROBABILITY"] = "0.6";
  keys["ROBOT_CONFIDENCE"] = "0.7";
  keys["BALL_CONFIDENCE"] = "0.6";
  keys["CONFIDENCE_SIGMA"] = "0.05";
  start(profile(keys));
  lockstep(0, 1212, [](double t) { return moving_robots(t, true); });
  stop();

  std::size_t frames = 0, robots = 0, balls = 0;
  std::vector<double> robot_confidence, ball_confidence;
  for (const auto& r : driver->frames(0)) {
    ++frames;
    robots += r.frame.robots_yellow.size() + r.frame.robots_blue.size();
    balls += r.frame.balls.size();
    for (const auto& d : r.frame.robots_yellow) robot_confidence.push_back(d.confidence);
    for (const auto& d : r.frame.robots_blue) robot_confidence.push_back(d.confidence);
    for (const auto& b : r.frame.balls) ball_confidence.push_back(b.confidence);
  }
  ASSERT_GE(frames, 1200u);
  auto expect_rate = [](std::size_t seen, std::size_t trials, double p, const char* what) {
    const double rate = static_cast<double>(seen) / static_cast<double>(trials);
    const double se = std::sqrt(p * (1 - p) / static_cast<double>(trials));
    EXPECT_NEAR(rate, p, 3 * se) << what << ": " << seen << " of " << trials;
  };
  expect_rate(robots, 10 * frames, 0.8, "robots");
  expect_rate(balls, frames, 0.6, "ball");
  for (double c : robot_confidence) ASSERT_TRUE(c >= 0 && c <= 1);
  const Stats rc = stats_of(robot_confidence), bc = stats_of(ball_confidence);
  EXPECT_NEAR(rc.mean, 0.7, 3 * rc.sd / std::sqrt(static_cast<double>(rc.n)));
  EXPECT_NEAR(bc.mean, 0.6, 3 * bc.sd / std::sqrt(static_cast<double>(bc.n)));
}

// False balls appear at dribblers, at the configured rate.
TEST_F(VisionProcess, FalseBallsAppearAtDribblersAtTheConfiguredRate) {
  auto keys = base_keys();
  keys["FRAME_RATE"] = "240";
  keys["FALSE_BALL_RATE"] = "3";
  keys["FALSE_BALL_SPREAD"] = "0.01";
  keys["FALSE_BALL_CONFIDENCE"] = "0.3";
  start(profile(keys));
  const World world = [](double t) { return moving_robots(t, false); };  // no real ball
  lockstep(0, 1212, world);
  stop();

  std::size_t frames = 0, false_balls = 0;
  for (const auto& r : driver->frames(0)) {
    ++frames;
    const Truth truth = world(r.frame.t_capture);
    for (const auto& b : r.frame.balls) {
      ++false_balls;
      EXPECT_NEAR(b.confidence, 0.3, 1e-6);
      double nearest = 1e9;
      for (const auto& robot : truth.robots) {
        const double reach = omni4().front_distance + kBallRadius;
        const Vector2d dribbler(robot.x + reach * std::cos(robot.orientation),
                                robot.y + reach * std::sin(robot.orientation));
        nearest = std::min(nearest, (Vector2d(b.x, b.y) - dribbler).norm());
      }
      EXPECT_LT(nearest, 5 * 0.01);  // within 5 spreads of some dribbler
    }
  }
  // Each robot in view makes one with probability 3 / 240 per frame.
  const double p = 3.0 / 240, trials = 10.0 * static_cast<double>(frames);
  EXPECT_NEAR(static_cast<double>(false_balls), p * trials, 3 * std::sqrt(trials * p * (1 - p)));
}

// Cameras: the shipped four-camera profile; who sees what follows from each
// camera's view on the ground, worked out here from the profile's numbers.
TEST_F(VisionProcess, ObjectsInAnOverlapAreSeenByBothCamerasOthersByOne) {
  const auto modern_path = config_dir() + "/vision/modern.cfg";
  start(dir.write("modern_lockstep.cfg",
                  "BASE = " + modern_path + "\nCAMERA_COUNT = 5\n" + marker_camera_keys(4)));
  const ubersim::ConfigFile modern = ubersim::ConfigFile::load(modern_path);
  std::vector<DownCamera> cameras;
  std::vector<double> phases;
  for (int k = 0; k < 4; ++k) {
    const std::string prefix = "CAMERA_" + std::to_string(k) + "_";
    const auto p = modern.reals(prefix + "POSITION", 3);
    const auto size = modern.integers(prefix + "IMAGE_SIZE", 2);
    ASSERT_EQ(modern.reals(prefix + "ORIENTATION_DEG", 3), std::vector<double>(3, 0.0));
    cameras.push_back({Vector3d(p[0], p[1], p[2]), modern.real(prefix + "FOCAL_LENGTH"),
                       size[0] / 2.0, size[1] / 2.0});
    phases.push_back(modern.real(prefix + "PHASE"));
  }
  const double rate = modern.real("FRAME_RATE");
  const double height = omni4().height;
  auto expected_cameras = [&](const Vector3d& p) {
    std::set<int> seen;
    for (int k = 0; k < 4; ++k) {
      const Vector2d px = cameras[k].pixel(p);
      if (px.x() >= 0 && px.x() < 2 * cameras[k].cx && px.y() >= 0 && px.y() < 2 * cameras[k].cy) {
        seen.insert(k);
      }
    }
    return seen;
  };
  // Robots on the centre line, at the centre spot, deep in quadrants.
  const std::vector<Vector2d> spots{{0.1, 1.5}, {4.0, 3.0}, {-4.0, -0.1}, {0.05, -0.05}, {-2, -3}};
  const Truth truth = [&] {
    Truth t;
    for (std::size_t i = 0; i < spots.size(); ++i) {
      TruthRobot r;
      r.id = static_cast<int>(i);
      r.x = spots[i].x();
      r.y = spots[i].y();
      t.robots.push_back(r);
    }
    t.ball_present = true;
    t.ball = Vector3d(1.5, 0.1, kBallRadius);
    return t;
  }();
  std::vector<std::size_t> expected_count(spots.size() + 1);
  for (std::size_t i = 0; i < spots.size(); ++i) {
    expected_count[i] = expected_cameras(Vector3d(spots[i].x(), spots[i].y(), height)).size();
  }
  // The layout really has overlaps of two and four cameras, and single views.
  EXPECT_EQ(expected_count[0], 2u);
  EXPECT_EQ(expected_count[1], 1u);
  EXPECT_EQ(expected_count[2], 2u);
  EXPECT_EQ(expected_count[3], 4u);
  EXPECT_EQ(expected_count[4], 1u);
  EXPECT_EQ(expected_cameras(truth.ball).size(), 2u);

  lockstep(
      0, 960, [&](double) { return truth; }, 4);
  stop();

  for (int k = 0; k < 4; ++k) {
    const auto frames = driver->frames(k);
    ASSERT_GE(frames.size(), 315u) << "camera " << k;
    std::map<int, int> robot_seen;
    int ball_seen = 0;
    for (std::size_t n = 0; n < frames.size(); ++n) {
      const auto& f = frames[n].frame;
      EXPECT_EQ(f.frame_number, static_cast<std::int64_t>(n));
      EXPECT_NEAR(f.t_capture, phases[k] + static_cast<double>(n) / rate, 1e-5);
      for (const auto& r : f.robots_yellow) ++robot_seen[r.robot_id];
      ball_seen += f.num_balls > 0;
    }
    const double n = static_cast<double>(frames.size());
    for (std::size_t i = 0; i < spots.size(); ++i) {
      const bool expected =
          expected_cameras(Vector3d(spots[i].x(), spots[i].y(), height)).count(k) > 0;
      const double seen = robot_seen[static_cast<int>(i)] / n;
      if (expected) {
        EXPECT_GT(seen, 0.9) << "camera " << k << " robot " << i;
      } else {
        EXPECT_EQ(seen, 0) << "camera " << k << " robot " << i;
      }
    }
    EXPECT_EQ(ball_seen > 0.9 * n, expected_cameras(truth.ball).count(k) > 0) << "camera " << k;
  }

  // Cameras 1 and 3 capture at the same instants; their views of the robot at
  // the centre spot carry independent noise (camera 3 also a calibration error).
  std::map<double, double> x1;
  for (const auto& r : driver->frames(1)) {
    for (const auto& d : r.frame.robots_yellow) {
      if (d.robot_id == 3) x1[r.frame.t_capture] = d.x;
    }
  }
  std::vector<double> differences;
  for (const auto& r : driver->frames(3)) {
    for (const auto& d : r.frame.robots_yellow) {
      const auto other = x1.find(r.frame.t_capture);
      if (d.robot_id == 3 && other != x1.end()) differences.push_back(d.x - other->second);
    }
  }
  ASSERT_GE(differences.size(), 300u);
  const double sigma = modern.real("ROBOT_SIGMA_X");
  // Difference of two independent draws: sd sigma * sqrt(2); n = 300 gives an
  // sd standard error of 4 %, so allow 15 %.
  EXPECT_NEAR(stats_of(differences).sd, sigma * std::sqrt(2.0), 0.15 * sigma * std::sqrt(2.0));
}

// Calibration error: the vision system's belief about camera 0 is off by a
// known translation and yaw; camera 1 hangs at the same place, calibrated.
TEST_F(VisionProcess, CalibrationErrorShiftsDetectionsByTheGeometricAmount) {
  const Vector3d position_error(0.03, -0.02, 0.1);
  const double yaw_error = 1.0 * M_PI / 180;
  auto keys = base_keys();
  keys["CAMERA_0_CALIBRATION_ERROR_POSITION"] = "0.03 -0.02 0.1";
  keys["CAMERA_0_CALIBRATION_ERROR_ORIENTATION_DEG"] = "0 0 1.0";
  keys["CAMERA_1_POSITION"] = "0.5 -0.3 4.0";
  keys["CAMERA_1_ORIENTATION_DEG"] = "0 0 0";
  keys["CAMERA_1_FOCAL_LENGTH"] = "400";
  keys["CAMERA_1_IMAGE_SIZE"] = "1280 960";
  keys["CAMERA_1_PHASE"] = "0";
  start(profile(keys, 2));
  const World world = [](double t) { return moving_robots(t, true); };
  lockstep(0, 120, world, 2);
  stop();

  // The believed camera C' = C + dC, turned by the yaw error about its centre:
  // the ray through a pixel meets the plane z = h at
  //   C' + (h - C'z) / (h - Cz) * Rz(yaw) (P - C)    (horizontally),
  // and every heading turns by the yaw error.
  const Vector3d c = kCamera.position, believed = c + position_error;
  auto expected = [&](const Vector3d& p) {
    const double s = (p.z() - believed.z()) / (p.z() - c.z());
    const Vector2d turned = Eigen::Rotation2Dd(yaw_error) * Vector2d((p - c).head<2>());
    return Vector2d(believed.head<2>() + s * turned);
  };
  const double height = omni4().height;
  int checked = 0;
  double largest_shift = 0;
  for (int camera : {0, 1}) {
    for (const auto& r : driver->frames(camera)) {
      const Truth truth = world(r.frame.t_capture);
      for (std::int8_t team : {ubersim::team_t::YELLOW, ubersim::team_t::BLUE}) {
        for (const auto* d : robots_in(r.frame, team)) {
          const TruthRobot* t = truth_robot(truth, team, d->robot_id);
          const Vector3d top(t->x, t->y, height);
          const Vector2d want = camera == 0 ? expected(top) : Vector2d(top.head<2>());
          EXPECT_NEAR(d->x, want.x(), 1e-6);
          EXPECT_NEAR(d->y, want.y(), 1e-6);
          EXPECT_NEAR(ubersim::wrap_angle(d->orientation - t->orientation),
                      camera == 0 ? yaw_error : 0.0, 1e-6);
          // The image itself does not change with what the system believes.
          EXPECT_NEAR(d->pixel_x, kCamera.pixel(top).x(), 1e-6);
          EXPECT_NEAR(d->pixel_y, kCamera.pixel(top).y(), 1e-6);
          if (camera == 0) largest_shift = std::max(largest_shift, (want - top.head<2>()).norm());
          ++checked;
        }
      }
      for (const auto& b : r.frame.balls) {
        const Vector2d want = camera == 0 ? expected(truth.ball) : Vector2d(truth.ball.head<2>());
        EXPECT_NEAR(b.x, want.x(), 1e-6);
        EXPECT_NEAR(b.y, want.y(), 1e-6);
      }
    }
  }
  EXPECT_GT(checked, 300);
  EXPECT_GT(largest_shift, 0.05);  // the error is large enough to matter
  // VISION_GEOMETRY tells the believed pose.
  ASSERT_FALSE(driver->geometries().empty());
  const auto& calibration = driver->geometries().back().cameras;
  ASSERT_EQ(calibration.size(), 3u);
  EXPECT_NEAR(calibration[0].position[0], believed.x(), 1e-12);
  EXPECT_NEAR(calibration[0].position[2], believed.z(), 1e-12);
  EXPECT_NEAR(calibration[1].position[0], c.x(), 1e-12);
}

// A camera set at run time (VISION_CAMERAS, as the SSL bridge sends for an
// SSL geometry's calibrations): from the next state on the new cameras decide
// which camera sees what, detect through their lens, and VISION_GEOMETRY
// reports them; a bad set is counted and changes nothing.
TEST_F(VisionProcess, CamerasSetAtRunTimeReplaceTheProfilesCameras) {
  auto keys = base_keys();
  keys["CAMERA_OVERLAP"] = "0.1";  // which camera sees what: regions (ER-Force's rule)
  keys["CAMERA_1_POSITION"] = "-2.5 0 4.0";
  keys["CAMERA_1_ORIENTATION_DEG"] = "0 0 0";
  keys["CAMERA_1_FOCAL_LENGTH"] = "400";
  keys["CAMERA_1_IMAGE_SIZE"] = "1280 960";
  keys["CAMERA_1_PHASE"] = "0";
  start(profile(keys, 2));
  // One robot at (1.5, -0.5): nearest camera 0 (at 0.5, -0.3), far from camera 1.
  const World world = [](double) {
    Truth truth;
    TruthRobot r;
    r.team = ubersim::team_t::BLUE;
    r.id = 4;
    r.x = 1.5;
    r.y = -0.5;
    truth.robots.push_back(r);
    return truth;
  };
  lockstep(0, 59, world, 2);

  // Camera 0 moves to the far left, camera 1 (a distorted lens without image
  // edge, as the official geometry's) next to the robot; the marker camera
  // (id 2) keeps its timing and goes where it owns no part of the field.
  const auto calibration = [](int id, double x, double y, double z, double f, int width, int height,
                              double distortion) {
    ubersim::camera_calibration_t c{};
    c.camera_id = id;
    c.focal_length = f;
    c.principal_x = width > 0 ? width / 2.0 : 300;
    c.principal_y = height > 0 ? height / 2.0 : 300;
    c.image_width = width;
    c.image_height = height;
    c.position[0] = x;
    c.position[1] = y;
    c.position[2] = z;
    c.orientation[1] = 1;  // w x y z = 0 1 0 0: straight down, rows along field -y
    c.distortion = distortion;
    return c;
  };
  ubersim::vision_cameras_t set{};
  set.sender = "test";
  set.cameras = {calibration(0, -2.5, 0.0, 4.0, 400, 1280, 960, 0),
                 calibration(1, 2.0, -0.5, 5.0, 390, 0, 0, 0.2),
                 calibration(2, 50, 50, 20, 10000, 4, 4, 0)};
  set.num_cameras = 3;
  ubersim::vision_cameras_t broken = set;
  broken.cameras[1].focal_length = std::nan("");
  driver->publish_cameras(broken);  // refused whole: nothing changes
  lockstep(60, 79, world, 2);
  driver->publish_cameras(set);
  lockstep(80, 171, world, 2);  // frames are published 12 steps (50 ms) after capture
  driver->listen(0.3);          // the geometry sent when the set was applied
  stop();

  const double switch_time = 80 * kDt;
  int before_0 = 0, before_1 = 0, after_0 = 0, after_1 = 0;
  for (int camera : {0, 1}) {
    for (const auto& r : driver->frames(camera)) {
      const auto robots = robots_in(r.frame, ubersim::team_t::BLUE);
      const bool before = r.frame.t_capture < switch_time - 1e-9;
      int& seen = camera == 0 ? (before ? before_0 : after_0) : (before ? before_1 : after_1);
      seen += static_cast<int>(robots.size());
      for (const auto* d : robots) {  // no calibration error: the truth, through any lens
        EXPECT_NEAR(d->x, 1.5, 1e-6);
        EXPECT_NEAR(d->y, -0.5, 1e-6);
      }
    }
  }
  EXPECT_EQ(before_0, 20);  // 60 Hz: steps 0, 4, ..., 76
  EXPECT_EQ(before_1, 0);
  EXPECT_EQ(after_0, 0);
  EXPECT_EQ(after_1, 20);  // steps 80 ... 156 (published by step 168)
  ASSERT_FALSE(driver->geometries().empty());
  const auto& reported = driver->geometries().back();
  ASSERT_EQ(reported.num_cameras, 3);
  EXPECT_DOUBLE_EQ(reported.cameras[1].position[0], 2.0);
  EXPECT_DOUBLE_EQ(reported.cameras[1].position[2], 5.0);
  EXPECT_DOUBLE_EQ(reported.cameras[1].focal_length, 390);
  EXPECT_DOUBLE_EQ(reported.cameras[1].distortion, 0.2);
  EXPECT_EQ(reported.cameras[1].image_width, 0);
  const auto summary = exit_summary(read_text(log));
  EXPECT_EQ(summary.at("camera sets applied"), 1);
  EXPECT_EQ(summary.at("camera sets invalid"), 1);
}

// A chipped ball is reported where the camera's ray through it meets the ground.
TEST_F(VisionProcess, ChippedBallIsReportedAtItsGroundProjection) {
  start(profile(base_keys()));
  const World world = [](double t) {
    Truth truth;
    truth.ball_present = true;
    const double z = kBallRadius + 4.0 * t - 4.905 * t * t;  // 4 m/s up: 0.8 m high at 0.41 s
    truth.ball = Vector3d(-1.0 + 2.0 * t, 0.5 + 0.5 * t, std::max(kBallRadius, z));
    return truth;
  };
  lockstep(0, 240, world);
  stop();
  const Vector3d c = kCamera.position;
  int checked = 0;
  double highest = 0, largest_shift = 0;
  for (const auto& r : driver->frames(0)) {
    const Vector3d ball = world(r.frame.t_capture).ball;
    ASSERT_EQ(r.frame.num_balls, 1);
    // Similar triangles from the camera centre down to the plane z = radius.
    const Vector2d ground =
        c.head<2>() + (ball - c).head<2>() * (c.z() - kBallRadius) / (c.z() - ball.z());
    EXPECT_NEAR(r.frame.balls[0].x, ground.x(), 1e-6) << "ball at height " << ball.z();
    EXPECT_NEAR(r.frame.balls[0].y, ground.y(), 1e-6) << "ball at height " << ball.z();
    EXPECT_NEAR(r.frame.balls[0].pixel_x, kCamera.pixel(ball).x(), 1e-6);
    EXPECT_NEAR(r.frame.balls[0].pixel_y, kCamera.pixel(ball).y(), 1e-6);
    highest = std::max(highest, ball.z());
    largest_shift = std::max(largest_shift, (ground - ball.head<2>()).norm());
    ++checked;
  }
  EXPECT_GT(checked, 55);
  EXPECT_GT(highest, 0.7);
  EXPECT_GT(largest_shift, 0.2);  // the projection is far from the ball's own position
}

namespace {

// Whether the ray from a point up to the camera passes through an upright
// robot (round, cut flat at its front), by walking up the ray in small steps.
bool hidden_by(const Vector3d& point, const Vector3d& camera, const TruthRobot& robot, int steps) {
  const auto& size = omni4();
  const Vector2d forward(std::cos(robot.orientation), std::sin(robot.orientation));
  for (int i = 0; i <= steps; ++i) {
    const double z = point.z() + (size.height - point.z()) * i / steps;
    const double s = (z - point.z()) / (camera.z() - point.z());
    const Vector2d d = (point + s * (camera - point)).head<2>() - Vector2d(robot.x, robot.y);
    if (d.norm() <= size.radius && d.dot(forward) <= size.front_distance) return true;
  }
  return false;
}

struct Visible {
  double fraction;
  Vector2d center;
};

// The visible part of the ball's disc, on an n x n grid (n = 80: fine).
Visible visible_part(const Vector3d& ball, const Vector3d& camera, const TruthRobot& robot,
                     int n = 80) {
  int total = 0, visible = 0;
  Vector2d sum = Vector2d::Zero();
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const Vector2d u(-1 + (2 * i + 1.0) / n, -1 + (2 * j + 1.0) / n);
      if (u.norm() > 1) continue;
      ++total;
      const Vector3d p = ball + kBallRadius * Vector3d(u.x(), u.y(), 0);
      if (!hidden_by(p, camera, robot, 4 * n)) {
        ++visible;
        sum += p.head<2>();
      }
    }
  }
  return {static_cast<double>(visible) / total, visible ? Vector2d(sum / visible) : Vector2d()};
}

}  // namespace

// A ball behind a robot, as one camera sees it: hidden, or reported at the
// centre of its visible part, depending on how much of it shows.
TEST_F(VisionProcess, BallBehindARobotIsHiddenOrShiftedAsConfigured) {
  auto keys = base_keys();
  keys["CAMERA_0_POSITION"] = "0 0 4.0";
  keys["BALL_MIN_VISIBLE_FRACTION"] = "0.5";
  // Camera 1 looks from the other side of the robot.
  keys["CAMERA_1_POSITION"] = "3.0 0 4.0";
  keys["CAMERA_1_ORIENTATION_DEG"] = "0 0 0";
  keys["CAMERA_1_FOCAL_LENGTH"] = "400";
  keys["CAMERA_1_IMAGE_SIZE"] = "1280 960";
  keys["CAMERA_1_PHASE"] = "0";
  start(profile(keys, 2));

  TruthRobot robot;  // facing camera 0, its round back away from it
  robot.x = 1.5;
  robot.orientation = M_PI;
  const Vector3d camera0(0, 0, 4.0);
  // Beside the robot's back, where camera 0's view of the ball is cut by the
  // robot's edge: find spots where 75 % and 25 % of the ball shows.
  const double touching = omni4().radius + kBallRadius;
  Vector3d mostly_visible, mostly_hidden;
  bool found_mostly_visible = false, found_mostly_hidden = false;
  for (int i = 0; i < 500; ++i) {  // y from 0.25 m towards the robot, 0.5 mm steps
    const Vector3d ball(1.6, 0.25 - 0.0005 * i, kBallRadius);
    if ((ball.head<2>() - Vector2d(robot.x, robot.y)).norm() < touching) break;
    const double fraction = visible_part(ball, camera0, robot, 24).fraction;  // coarse: a search
    if (!found_mostly_visible && fraction < 0.75) {
      mostly_visible = ball;
      found_mostly_visible = true;
    }
    if (fraction < 0.25) {
      mostly_hidden = ball;
      found_mostly_hidden = true;
      break;
    }
  }
  ASSERT_TRUE(found_mostly_visible && found_mostly_hidden);
  const Vector3d behind(robot.x + touching, 0, kBallRadius);  // wholly hidden from camera 0
  const Vector3d free_ball(1.5, 0.6, kBallRadius);
  const std::vector<Vector3d> scenes{behind, mostly_visible, mostly_hidden, free_ball};

  // Each scene holds for a quarter second of sim time.
  const World world = [&](double t) {
    Truth truth;
    truth.robots.push_back(robot);
    truth.ball_present = true;
    truth.ball = scenes[std::min<std::size_t>(3, static_cast<std::size_t>(t / 0.25))];
    return truth;
  };
  lockstep(0, 4 * 60 + 12, world, 2);
  stop();

  std::vector<Visible> expected_view;
  for (const Vector3d& ball : scenes) expected_view.push_back(visible_part(ball, camera0, robot));
  std::vector<int> seen0(4), frames0(4), seen1(4);
  for (int camera : {0, 1}) {
    for (const auto& r : driver->frames(camera)) {
      const auto scene =
          std::min<std::size_t>(3, static_cast<std::size_t>(r.frame.t_capture / 0.25));
      const Vector3d& ball = scenes[scene];
      if (camera == 1) {
        // From the other side the robot hides nothing: the ball shows whole.
        ASSERT_EQ(r.frame.num_balls, 1) << "scene " << scene;
        EXPECT_NEAR(r.frame.balls[0].x, ball.x(), 1e-6);
        ++seen1[scene];
        continue;
      }
      ++frames0[scene];
      if (r.frame.num_balls == 0) continue;
      ++seen0[scene];
      const Visible& expected = expected_view[scene];
      // The centre of the visible part, to within the emulator's sampling (~1 mm).
      EXPECT_NEAR(r.frame.balls[0].x, expected.center.x(), 0.0015) << "scene " << scene;
      EXPECT_NEAR(r.frame.balls[0].y, expected.center.y(), 0.0015) << "scene " << scene;
      // Less of the ball, less confidence.
      EXPECT_NEAR(r.frame.balls[0].confidence, 0.9 * expected.fraction, 0.05) << "scene " << scene;
    }
  }
  for (int scene = 0; scene < 4; ++scene) ASSERT_GE(frames0[scene], 14) << scene;
  EXPECT_EQ(seen0[0], 0);           // wholly hidden
  EXPECT_EQ(seen0[1], frames0[1]);  // 75 % shows: reported, shifted
  EXPECT_EQ(seen0[2], 0);           // 25 % shows: below the 50 % threshold
  EXPECT_EQ(seen0[3], frames0[3]);  // free
  EXPECT_GT((expected_view[1].center - mostly_visible.head<2>()).norm(), 0.003);  // a real shift
  EXPECT_GT(expected_view[1].fraction, 0.6);
  EXPECT_LT(expected_view[2].fraction, 0.4);
  for (int scene = 0; scene < 4; ++scene) EXPECT_GE(seen1[scene], 14) << scene;
}

// Bad input on SIM_STATE is counted and skipped; the process carries on.
TEST_F(VisionProcess, MalformedAndOutOfOrderSimStatesAreCountedAndSkipped) {
  start(profile(base_keys()));
  const World world = [](double t) { return moving_robots(t, true); };
  lockstep(0, 100, world);

  // Bytes that do not decode: garbage, a truncated state, nothing, a state with a tail.
  std::vector<std::uint8_t> garbage(300);
  for (std::size_t i = 0; i < garbage.size(); ++i) garbage[i] = static_cast<std::uint8_t>(i * 37);
  driver->publish_raw_state(garbage);
  const auto good = make_state(101, world(101 * kDt));
  std::vector<std::uint8_t> encoded(static_cast<std::size_t>(good.getEncodedSize()));
  good.encode(encoded.data(), 0, static_cast<int>(encoded.size()));
  driver->publish_raw_state(std::vector<std::uint8_t>(encoded.begin(), encoded.begin() + 40));
  driver->publish_raw_state({});
  auto with_tail = encoded;
  with_tail.push_back(0);
  driver->publish_raw_state(with_tail);
  // States that decode but make no sense, or come too late.
  auto nan_pose = make_state(101, world(101 * kDt));
  nan_pose.robots[2].y = std::nan("");
  driver->publish_state(nan_pose);
  auto no_team = make_state(101, world(101 * kDt));
  no_team.robots[0].team = 5;
  driver->publish_state(no_team);
  auto infinite_ball = make_state(101, world(101 * kDt));
  infinite_ball.ball.position[0] = INFINITY;
  driver->publish_state(infinite_ball);
  driver->publish_state(make_state(50, world(50 * kDt)));    // out of order
  driver->publish_state(make_state(100, world(100 * kDt)));  // the same step again

  lockstep(101, 300, world);
  ASSERT_TRUE(emulator->running());
  stop();
  const auto summary = exit_summary(read_text(log));
  EXPECT_EQ(summary.at("undecodable"), 4) << read_text(log);
  EXPECT_EQ(summary.at("invalid"), 3);
  EXPECT_EQ(summary.at("out of order"), 1);
  EXPECT_EQ(summary.at("repeated"), 1);
  // Frames went on, consecutive and finite, as if nothing had happened.
  const auto frames = driver->frames(0);
  ASSERT_GE(frames.size(), 70u);
  for (std::size_t n = 0; n < frames.size(); ++n) {
    const auto& f = frames[n].frame;
    EXPECT_EQ(f.frame_number, static_cast<std::int64_t>(n));
    EXPECT_NEAR(f.t_capture, static_cast<double>(n) / 60, 1e-9);
    for (const auto& r : f.robots_yellow) EXPECT_TRUE(std::isfinite(r.x + r.y + r.orientation));
    for (const auto& b : f.balls) EXPECT_TRUE(std::isfinite(b.x + b.y));
  }
}

// A reset (sim time back to 0): pending frames are dropped, capture restarts
// at the phase, frame numbers keep increasing.
TEST_F(VisionProcess, ResetRestartsCaptureAndKeepsFrameNumbersIncreasing) {
  start(profile(base_keys()));
  const World world = [](double t) { return moving_robots(t, true); };
  lockstep(0, 240, world);
  const std::size_t before = driver->frames(0).size();
  lockstep(0, 120, world);
  stop();
  const auto frames = driver->frames(0);
  ASSERT_GT(frames.size(), before + 20);
  const auto& last_before = frames[before - 1].frame;
  EXPECT_NEAR(last_before.t_capture, (240 - 12) * kDt, 1e-9);  // 50 ms latency = 12 steps
  const auto& first_after = frames[before].frame;
  EXPECT_NEAR(first_after.t_capture, 0.0, 1e-12);
  EXPECT_GT(first_after.frame_number, last_before.frame_number);
  for (std::size_t n = before; n < frames.size(); ++n) {
    EXPECT_LT(frames[n].frame.t_capture, 0.5 + 1e-9);  // nothing from before the reset
    if (n > before) {
      EXPECT_EQ(frames[n].frame.frame_number, frames[n - 1].frame.frame_number + 1);
    }
  }
  const auto summary = exit_summary(read_text(log));
  EXPECT_EQ(summary.at("resets"), 1);
  EXPECT_GT(summary.at("dropped at reset"), 0);
}

// VISION_GEOMETRY: the --field geometry at start, physics' geometry once it
// arrives, then again every GEOMETRY_PERIOD (wall clock).
TEST_F(VisionProcess, GeometryIsPublishedAtStartOnChangeAndPeriodically) {
  auto keys = base_keys();
  keys["GEOMETRY_PERIOD"] = "0.2";
  keys["CAMERA_0_CALIBRATION_ERROR_POSITION"] = "0.01 0.02 0.03";
  start(profile(keys), {"--field", "division_a"});
  driver->listen(1.5);
  stop();
  const auto& geometries = driver->geometries();
  ASSERT_GE(geometries.size(), 4u);
  EXPECT_EQ(geometries.front().field.name, "division_a");
  EXPECT_DOUBLE_EQ(geometries.front().field.field_length, 12.0);
  EXPECT_EQ(geometries.back().field.name, "division_b");  // what "physics" sent
  EXPECT_DOUBLE_EQ(geometries.back().field.field_length, 9.0);
  ASSERT_EQ(geometries.back().num_cameras, 2);
  EXPECT_NEAR(geometries.back().cameras[0].position[0], 0.51, 1e-12);
  EXPECT_NEAR(geometries.back().cameras[0].position[1], -0.28, 1e-12);
  EXPECT_DOUBLE_EQ(geometries.back().cameras[0].focal_length, 400);
}

// Same seed and same states give identical frames; another seed does not.
TEST_F(VisionProcess, SameSeedGivesIdenticalFrames) {
  auto keys = base_keys();
  keys["LATENCY_JITTER"] = "0.004";
  keys["ROBOT_SIGMA_X"] = "0.01";
  keys["BALL_SIGMA_Y"] = "0.01";
  keys["ROBOT_DETECTION_PROBABILITY"] = "0.7";
  keys["CONFIDENCE_SIGMA"] = "0.1";
  keys["FALSE_BALL_RATE"] = "1";
  const std::string path = profile(keys);
  const World world = [](double t) { return moving_robots(t, true); };
  auto run = [&](const std::string& seed) {
    start(path, {"--seed", seed});
    lockstep(0, 300, world);
    stop();
    std::vector<std::vector<std::uint8_t>> encoded;
    for (const auto& r : driver->frames(0)) {
      std::vector<std::uint8_t> bytes(static_cast<std::size_t>(r.frame.getEncodedSize()));
      r.frame.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
      encoded.push_back(std::move(bytes));
      encoded.push_back({static_cast<std::uint8_t>(r.published_at_step % 256)});
    }
    return encoded;
  };
  const auto a = run("5");
  const auto b = run("5");
  const auto c = run("6");
  ASSERT_GE(a.size(), 2 * 70u);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
}

// What the vision says to physics besides frames (issue 18): in real time
// (states with speed 1, paced at 240 Hz of wall time) its truth demand every
// few frames (it announces 8 frames' release times at once) and its schedule
// only as the 10 Hz repetition, listing no frame; in sync mode (speed 0) a
// schedule lists every frame before it goes out.
// As fast as possible physics runs at most kVisionLead ahead of the last
// state the vision acknowledged (docs/vision.md, "As fast as possible"): with
// a camera too slow to say anything for a while, the vision still
// acknowledges a state every kVisionAckInterval of sim time.
TEST_F(VisionProcess, AsFastAsPossibleAStateIsAcknowledgedEveryAckIntervalOfSimTime) {
  auto keys = base_keys();
  keys["FRAME_RATE"] = "2";
  keys["CAMERA_COUNT"] = "1";  // no marker camera: it would speak at every step
  std::string text;
  for (const auto& [key, value] : keys) text.append(key).append(" = ").append(value).append("\n");
  start(dir.write("slow_camera.cfg", text));
  ubersim::MessageBus spy(ubersim::with_receive_buffer(ubersim::default_lcm_url()));
  const ubersim::ChannelNames channels;
  std::vector<double> acknowledged;
  ubersim::subscribe(
      spy, channels, ubersim::topics::kVisionSchedule, [&](const ubersim::vision_schedule_t& s) {
        if (s.step >= 0 && (acknowledged.empty() || s.t_state != acknowledged.back())) {
          acknowledged.push_back(s.t_state);
        }
      });
  constexpr std::int64_t kStride = 5;  // a state every 20.8 ms of sim time
  constexpr std::int64_t kLast = 480;  // 2 s
  for (std::int64_t step = 0; step <= kLast; step += kStride) {
    driver->publish_state(make_state(step, moving_robots(static_cast<double>(step) * kDt, true)));
    spy.handle_pending();
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  driver->listen(0.3);
  spy.handle_pending();
  stop();
  ASSERT_GE(acknowledged.size(), 2u);
  // The last state itself when it came kVisionAckInterval after the last acknowledged one.
  EXPECT_GT(acknowledged.back(),
            static_cast<double>(kLast / kStride * kStride) * kDt - ubersim::kVisionAckInterval);
  double widest = 0;
  for (std::size_t i = 1; i < acknowledged.size(); ++i) {
    widest = std::max(widest, acknowledged[i] - acknowledged[i - 1]);
  }
  // The first state at least kVisionAckInterval after the last acknowledged one.
  EXPECT_LE(widest, ubersim::kVisionAckInterval + static_cast<double>(kStride) * kDt + 1e-9);
  // 2 frames a second would say something only 4 times a second.
  EXPECT_GE(acknowledged.size(), 2.0 / (ubersim::kVisionAckInterval + kStride * kDt));
}

TEST_F(VisionProcess, InRealTimeDemandsComeEveryFewFramesAndSchedulesOnlyAsRepetitions) {
  start("cmdragons02");
  ubersim::MessageBus spy(ubersim::with_receive_buffer(ubersim::default_lcm_url()));
  const ubersim::ChannelNames channels;
  int demands = 0;
  int schedules = 0;
  int frames_listed = 0;
  ubersim::subscribe(spy, channels, ubersim::topics::kTruthDemand,
                     [&](const ubersim::truth_demand_t&) { ++demands; });
  ubersim::subscribe(spy, channels, ubersim::topics::kVisionSchedule,
                     [&](const ubersim::vision_schedule_t& s) {
                       ++schedules;
                       frames_listed += s.num_frames;
                     });
  const auto pace_start = std::chrono::steady_clock::now();
  constexpr std::int64_t kRealTimeSteps = 480;  // 2 s
  for (std::int64_t step = 0; step <= kRealTimeSteps; ++step) {
    ubersim::sim_state_t state =
        make_state(step, moving_robots(static_cast<double>(step) * kDt, true));
    state.speed_factor = 1;
    std::this_thread::sleep_until(pace_start + std::chrono::microseconds(step * 1000000 / 240));
    driver->publish_state(state);
    spy.handle_pending();
  }
  driver->listen(0.3);
  spy.handle_pending();
  // A loaded machine stretches the run: what comes by the wall clock is
  // bounded by the wall time it took.
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - pace_start).count();
  const std::size_t real_time_frames = driver->frames(0).size();
  EXPECT_GE(real_time_frames, 55u);  // 30 Hz for 2 s, less the 66 ms latency
  // One at the first state, then every 6 frames, plus the once-a-second refresh.
  EXPECT_LE(demands, static_cast<int>(real_time_frames) / 6 + static_cast<int>(wall) + 3);
  EXPECT_GE(demands, static_cast<int>(real_time_frames) / 8);
  EXPECT_LE(schedules, static_cast<int>(10 * wall) + 3);  // the 10 Hz repetition
  EXPECT_EQ(frames_listed, 0);

  frames_listed = 0;
  for (std::int64_t step = kRealTimeSteps + 1; step <= kRealTimeSteps + 240; ++step) {
    driver->publish_state(make_state(step, moving_robots(static_cast<double>(step) * kDt, true)));
    spy.handle_pending();
    std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
  driver->listen(0.3);
  spy.handle_pending();
  const std::size_t sync_frames = driver->frames(0).size() - real_time_frames;
  EXPECT_GE(sync_frames, 25u);
  EXPECT_EQ(frames_listed, static_cast<int>(sync_frames));
  stop();
}

// Physics in sync mode starts on the vision's schedule and must know its truth
// demand by then: at start the demand goes out before the first ("listening")
// schedule, and the demand of the first state and of a reset right before the
// schedule of that state.
TEST_F(VisionProcess, TheDemandGoesOutBeforeTheScheduleThatNeedsIt) {
  struct Said {
    bool demand;
    std::int64_t step;  // a schedule's
  };
  std::vector<Said> said;
  // Listening before the child can speak; one socket, so in the order sent.
  ubersim::MessageBus spy(ubersim::with_receive_buffer(ubersim::default_lcm_url()));
  const ubersim::ChannelNames channels;
  ubersim::subscribe(spy, channels, ubersim::topics::kTruthDemand,
                     [&](const ubersim::truth_demand_t& d) {
                       if (d.consumer == "vision") said.push_back({true, 0});
                     });
  ubersim::subscribe(spy, channels, ubersim::topics::kVisionSchedule,
                     [&](const ubersim::vision_schedule_t& s) {
                       said.push_back({false, s.step});
                     });
  start(profile(base_keys()));
  const World world = [](double t) { return moving_robots(t, false); };
  lockstep(0, 60, world);
  lockstep(0, 30, world);  // a reset
  stop();
  while (spy.handle_pending() > 0) {
  }

  ASSERT_GE(said.size(), 2u);
  EXPECT_TRUE(said[0].demand);
  EXPECT_FALSE(said[1].demand);
  EXPECT_EQ(said[1].step, -1);
  // The schedules of step 0: the first state's, then the reset's (not their
  // repetitions: the same step as the schedule before).
  int step0_schedules = 0;
  std::int64_t last_step = -1;
  for (std::size_t i = 0; i < said.size(); ++i) {
    if (said[i].demand) continue;
    const bool repetition = said[i].step == last_step;
    last_step = said[i].step;
    if (said[i].step != 0 || repetition) continue;
    ++step0_schedules;
    ASSERT_GT(i, 0u);
    EXPECT_TRUE(said[i - 1].demand) << "schedule of step 0 number " << step0_schedules;
  }
  EXPECT_EQ(step0_schedules, 2);
}
