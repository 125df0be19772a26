// ER-Force's camera model in the vision emulator core, each part measured:
// which camera sees what (regions and camera_overlap), cameras replaced at
// run time (VISION_CAMERAS), camera_position_error, object_position_offset,
// the ball's area and its noise (stddev_ball_area), and lens distortion.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <stdexcept>
#include <ubersim/team_t.hpp>
#include <vector>

#include "ubersim/config.hpp"
#include "ubersim/emulator_realism.hpp"
#include "ubersim/vision/pinhole_camera.hpp"
#include "ubersim/vision/vision_emulator.hpp"

using ubersim::camera_calibration_t;
using ubersim::ConfigFile;
using ubersim::emulator_realism_t;
using ubersim::sim_state_t;
using ubersim::vision_cameras_t;
using ubersim::vision_frame_t;
using ubersim::vision::RobotSize;
using ubersim::vision::RobotSizes;
using ubersim::vision::VisionEmulator;
using ubersim::vision::VisionProfile;

namespace {

constexpr double kDt = 1.0 / 240;
constexpr double kRobotHeight = 0.12;   // m, the test's robot type
constexpr double kBallRadius = 0.0215;  // m

// Two cameras 4 m up at x = -1 and x = +1 whose images both cover the middle
// of the field; 60 Hz each; noise as given.
VisionProfile profile(double robot_sigma, double ball_sigma, const std::string& extra = "") {
  const std::string text =
      "SEED = 3\nFRAME_RATE = 60\nLATENCY = 0\nLATENCY_JITTER = 0\n"
      "PROCESSING_TIME = 0\nGEOMETRY_PERIOD = 1\n"
      "ROBOT_SIGMA_X = " +
      std::to_string(robot_sigma) + "\nROBOT_SIGMA_Y = " + std::to_string(robot_sigma) +
      "\nROBOT_SIGMA_ORIENTATION = 0\nBALL_SIGMA_X = " + std::to_string(ball_sigma) +
      "\nBALL_SIGMA_Y = " + std::to_string(ball_sigma) +
      R"(
ROBOT_DETECTION_PROBABILITY = 1
BALL_DETECTION_PROBABILITY = 1
ROBOT_CONFIDENCE = 1
BALL_CONFIDENCE = 1
CONFIDENCE_SIGMA = 0
FALSE_BALL_RATE = 0
FALSE_BALL_SPREAD = 0
FALSE_BALL_CONFIDENCE = 0
BALL_MIN_VISIBLE_FRACTION = 0
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
CAMERA_1_PHASE = 0
)" + extra;
  return ubersim::vision::load_vision_profile(ConfigFile::parse(text, "erforce_model.cfg"),
                                              "erforce_model");
}

RobotSizes sizes() {
  return RobotSizes([](const std::string& type) -> RobotSize {
    if (type == "test") return RobotSize{0.09, kRobotHeight, 0.07};
    throw std::runtime_error("no such robot type");
  });
}

struct Placed {
  double x = 0;
  double y = 0;
};

// Still yellow robots (ids 0, 1, ...) at `robots`, the ball at `ball` on the ground.
sim_state_t world(std::int64_t step, const std::vector<Placed>& robots, const Placed& ball) {
  sim_state_t s{};
  s.sim_time = static_cast<double>(step) * kDt;
  s.step = step;
  s.dt = kDt;
  s.speed_factor = 1;
  s.ball_present = true;
  s.ball.position[0] = ball.x;
  s.ball.position[1] = ball.y;
  s.ball.position[2] = kBallRadius;
  s.ball.orientation[0] = 1;
  for (std::size_t i = 0; i < robots.size(); ++i) {
    ubersim::robot_state_t r{};
    r.team = ubersim::team_t::YELLOW;
    r.robot_id = static_cast<std::int32_t>(i);
    r.robot_type = "test";
    r.x = robots[i].x;
    r.y = robots[i].y;
    r.body.orientation[0] = 1;
    s.robots.push_back(r);
  }
  s.num_robots = static_cast<std::int32_t>(s.robots.size());
  return s;
}

std::vector<vision_frame_t> run(VisionEmulator& emulator, std::int64_t first, std::int64_t last,
                                const std::vector<Placed>& robots, const Placed& ball = {0, 3}) {
  std::vector<vision_frame_t> frames;
  for (std::int64_t step = first; step <= last; ++step) {
    for (auto& f : emulator.on_sim_state(world(step, robots, ball)).frames) {
      frames.push_back(std::move(f));
    }
  }
  return frames;
}

// Which cameras saw robot `id`, counted over the frames.
std::map<int, int> sightings(const std::vector<vision_frame_t>& frames, int id) {
  std::map<int, int> seen;
  for (const auto& f : frames) {
    for (const auto& r : f.robots_yellow) {
      if (r.robot_id == id) ++seen[f.camera_id];
    }
  }
  return seen;
}

struct Mean {
  double sum = 0;
  double sum_sq = 0;
  int n = 0;
  void add(double v) {
    sum += v;
    sum_sq += v * v;
    ++n;
  }
  double mean() const { return sum / n; }
  double sd() const { return std::sqrt((sum_sq - sum * sum / n) / (n - 1)); }
  double standard_error() const { return sd() / std::sqrt(n); }
};

camera_calibration_t straight_down(int id, double x, double y, double z) {
  camera_calibration_t c{};
  c.camera_id = id;
  c.focal_length = 390;
  c.principal_x = c.principal_y = 300;
  c.position[0] = x;
  c.position[1] = y;
  c.position[2] = z;
  c.orientation[1] = 1;  // w x y z = 0 1 0 0: 180 deg about x, looking straight down
  return c;
}

vision_cameras_t camera_set(std::vector<camera_calibration_t> cameras) {
  vision_cameras_t set{};
  set.sender = "test";
  set.cameras = std::move(cameras);
  set.num_cameras = static_cast<std::int32_t>(set.cameras.size());
  return set;
}

}  // namespace

TEST(ErForceCameraModel, CameraOverlapDecidesWhichCameraSeesAPointNearTheBorder) {
  // Robot 0 at x = 0.2 and robot 1 at x = 0.4: both in both images.
  const std::vector<Placed> robots{{0.2, 0.5}, {0.4, -0.5}};
  VisionEmulator emulator(profile(0, 0), sizes());
  auto frames = run(emulator, 0, 239, robots);
  EXPECT_EQ(sightings(frames, 0), (std::map<int, int>{{0, 60}, {1, 60}}));  // images only
  EXPECT_EQ(sightings(frames, 1), (std::map<int, int>{{0, 60}, {1, 60}}));

  // Camera 0 (at x = -1) owns x <= 0 and sees 0.3 m past it: robot 0, not robot 1.
  emulator_realism_t overlap = ubersim::unchanged_realism();
  overlap.camera_overlap = 0.3;
  ASSERT_EQ(emulator.apply_realism(overlap), "");
  frames = run(emulator, 240, 479, robots);
  EXPECT_EQ(sightings(frames, 0), (std::map<int, int>{{0, 60}, {1, 60}}));
  EXPECT_EQ(sightings(frames, 1), (std::map<int, int>{{1, 60}}));

  // 0.1 m: neither.
  overlap.camera_overlap = 0.1;
  ASSERT_EQ(emulator.apply_realism(overlap), "");
  frames = run(emulator, 480, 719, robots);
  EXPECT_EQ(sightings(frames, 0), (std::map<int, int>{{1, 60}}));
  EXPECT_EQ(sightings(frames, 1), (std::map<int, int>{{1, 60}}));
}

TEST(ErForceCameraModel, ProfileKeyCameraOverlapSetsTheRegionsFromTheStart) {
  VisionEmulator emulator(profile(0, 0, "CAMERA_OVERLAP = 0.3\n"), sizes());
  const auto frames = run(emulator, 0, 239, {{0.2, 0.5}, {0.4, -0.5}, {-0.35, 0}});
  EXPECT_EQ(sightings(frames, 1), (std::map<int, int>{{1, 60}}));
  EXPECT_EQ(sightings(frames, 2), (std::map<int, int>{{0, 60}}));
}

TEST(ErForceCameraModel, CamerasSetAtRunTimeChangeWhichCameraSeesWhat) {
  VisionEmulator emulator(profile(0, 0, "CAMERA_OVERLAP = 0\n"), sizes());
  const std::vector<Placed> robots{{-0.5, 0.2}};
  auto before = run(emulator, 0, 239, robots);
  EXPECT_EQ(sightings(before, 0), (std::map<int, int>{{0, 60}}));
  std::int64_t last_number_0 = -1;
  for (const auto& f : before) {
    if (f.camera_id == 0) last_number_0 = f.frame_number;
  }

  // Camera 0 moves to the far right, camera 1 to the left, a camera 2 is added
  // in the middle of the far half: robot 0 is now camera 1's.
  ASSERT_EQ(
      emulator.apply_cameras(camera_set(
          {straight_down(0, 3, 0, 6), straight_down(1, -2, 0, 6), straight_down(2, 0, 3, 6)})),
      "");
  auto after = run(emulator, 240, 479, robots);
  EXPECT_EQ(sightings(after, 0), (std::map<int, int>{{1, 60}}));
  // Camera 0 counts on; the new camera 2 captures with camera 0's rate and phase.
  std::map<int, std::vector<const vision_frame_t*>> by_camera;
  for (const auto& f : after) by_camera[f.camera_id].push_back(&f);
  ASSERT_EQ(by_camera.size(), 3u);
  EXPECT_EQ(by_camera[0].front()->frame_number, last_number_0 + 1);
  EXPECT_EQ(by_camera[2].size(), 60u);
  EXPECT_EQ(by_camera[2].front()->frame_number, 0);
  EXPECT_NEAR(by_camera[2].front()->t_capture, by_camera[0].front()->t_capture, 1e-12);
  // No calibration error: a camera from a calibration reports the truth.
  for (const auto& r : by_camera[1].front()->robots_yellow) {
    EXPECT_NEAR(r.x, -0.5, 1e-9);
    EXPECT_NEAR(r.y, 0.2, 1e-9);
  }
  // VISION_GEOMETRY reports the new cameras (distortion included).
  const auto geometry = emulator.geometry_message();
  ASSERT_EQ(geometry.num_cameras, 3);
  EXPECT_DOUBLE_EQ(geometry.cameras[1].position[0], -2);
  EXPECT_DOUBLE_EQ(geometry.cameras[2].position[1], 3);
  EXPECT_DOUBLE_EQ(geometry.cameras[2].focal_length, 390);
  EXPECT_EQ(emulator.stats().camera_sets_applied, 1u);
}

TEST(ErForceCameraModel, WithoutAnOverlapCamerasFromCalibrationsUseErForcesDefault) {
  VisionEmulator emulator(profile(0, 0), sizes());
  ASSERT_LT(emulator.profile().camera_overlap, 0);
  ASSERT_EQ(emulator.apply_cameras(
                camera_set({straight_down(0, -3.01, 0, 6), straight_down(1, 3.01, 0, 6)})),
            "");
  EXPECT_DOUBLE_EQ(emulator.profile().camera_overlap, 0.3);
  // The calibrations have no image size: the regions alone decide.
  const auto frames = run(emulator, 0, 239, {{0.25, 0}, {0.35, 0}, {-5.9, 4.4}});
  EXPECT_EQ(sightings(frames, 0), (std::map<int, int>{{0, 60}, {1, 60}}));
  EXPECT_EQ(sightings(frames, 1), (std::map<int, int>{{1, 60}}));
  EXPECT_EQ(sightings(frames, 2), (std::map<int, int>{{0, 60}}));
}

TEST(ErForceCameraModel, InvalidCameraSetsAreRefusedWholeAndCounted) {
  VisionEmulator emulator(profile(0, 0), sizes());
  auto nan_focal = straight_down(0, 0, 0, 5);
  nan_focal.focal_length = std::nan("");
  auto sideways = straight_down(1, 0, 0, 5);
  sideways.orientation[0] = sideways.orientation[1] = std::sqrt(0.5);  // 90 deg about x
  auto low = straight_down(1, 0, 0, 0.2);
  auto bad_distortion = straight_down(1, 0, 0, 5);
  bad_distortion.distortion = INFINITY;
  auto not_unit = straight_down(1, 0, 0, 5);
  not_unit.orientation[0] = 0.7;
  for (const vision_cameras_t& set :
       {camera_set({nan_focal}), camera_set({straight_down(0, 0, 0, 5), sideways}),
        camera_set({low}), camera_set({bad_distortion}), camera_set({not_unit}),
        camera_set({straight_down(3, 0, 0, 5), straight_down(3, 1, 0, 5)}), camera_set({})}) {
    EXPECT_NE(emulator.apply_cameras(set), "");
  }
  vision_cameras_t lying = camera_set({straight_down(0, 0, 0, 5)});
  lying.num_cameras = 2;
  EXPECT_NE(emulator.apply_cameras(lying), "");
  EXPECT_EQ(emulator.stats().camera_sets_invalid, 8u);
  EXPECT_EQ(emulator.camera_count(), 2u);
  EXPECT_DOUBLE_EQ(emulator.geometry_message().cameras[0].position[0], -1);
}

TEST(ErForceCameraModel, CameraPositionErrorMovesTheReportedCentreAndWhatIsAboveTheGround) {
  const double error = 0.1;    // m
  const double sigma = 0.002;  // m of noise, so that the mean is a measurement
  VisionEmulator emulator(profile(sigma, sigma), sizes());
  emulator_realism_t realism = ubersim::unchanged_realism();
  realism.camera_position_error = error;
  ASSERT_EQ(emulator.apply_realism(realism), "");

  // Reported centres: moved by the error in ER-Force's direction.
  const Eigen::Vector3d direction = Eigen::Vector3d(0.7, -0.3, 0.05).normalized();
  const auto geometry = emulator.geometry_message();
  for (int k = 0; k < 2; ++k) {
    const Eigen::Vector3d truth = emulator.camera(static_cast<std::size_t>(k)).truth().position();
    const Eigen::Vector3d reported(geometry.cameras[k].position[0], geometry.cameras[k].position[1],
                                   geometry.cameras[k].position[2]);
    EXPECT_NEAR((reported - truth - error * direction).norm(), 0, 1e-12);
  }

  // The field mapping stays right: a robot's top (0.12 m up) is placed on the
  // line from its ground point to the reported centre, so it moves by about
  // error x height / camera height (3 mm); the ball (centre 21.5 mm up) by
  // about 0.5 mm.
  const Placed robot{-0.6, 0.4};
  const Placed ball{-0.8, -0.3};
  const auto predicted = [&](const Placed& p, double height) {
    const Eigen::Vector3d camera = emulator.camera(0).truth().position();
    const Eigen::Vector3d top(p.x, p.y, height);
    const Eigen::Vector3d ground = camera + (top - camera) * (camera.z() / (camera.z() - height));
    const Eigen::Vector3d centre = camera + error * direction;
    return Eigen::Vector2d((ground + (centre - ground) * (height / centre.z())).head<2>());
  };
  Mean dx, dy, bx, by;
  for (const auto& f : run(emulator, 0, 4799, {robot}, ball)) {
    if (f.camera_id != 0) continue;
    for (const auto& r : f.robots_yellow) {
      dx.add(r.x - robot.x);
      dy.add(r.y - robot.y);
    }
    for (const auto& b : f.balls) {
      bx.add(b.x - ball.x);
      by.add(b.y - ball.y);
    }
  }
  ASSERT_EQ(dx.n, 1200);
  const Eigen::Vector2d robot_shift =
      predicted(robot, kRobotHeight) - Eigen::Vector2d(robot.x, robot.y);
  const Eigen::Vector2d ball_shift = predicted(ball, kBallRadius) - Eigen::Vector2d(ball.x, ball.y);
  EXPECT_NEAR(robot_shift.norm(), error * kRobotHeight / 4, 0.0005);  // the size of the effect
  EXPECT_NEAR(dx.mean(), robot_shift.x(), 3 * dx.standard_error());
  EXPECT_NEAR(dy.mean(), robot_shift.y(), 3 * dy.standard_error());
  EXPECT_NEAR(bx.mean(), ball_shift.x(), 3 * bx.standard_error());
  EXPECT_NEAR(by.mean(), ball_shift.y(), 3 * by.standard_error());
  std::printf(
      "camera_position_error %.3f m: robot shift measured (%.3f, %.3f) mm, predicted "
      "(%.3f, %.3f) mm; ball (%.3f, %.3f) mm vs (%.3f, %.3f) mm\n",
      error, 1e3 * dx.mean(), 1e3 * dy.mean(), 1e3 * robot_shift.x(), 1e3 * robot_shift.y(),
      1e3 * bx.mean(), 1e3 * by.mean(), 1e3 * ball_shift.x(), 1e3 * ball_shift.y());
}

TEST(ErForceCameraModel, ObjectPositionOffsetShiftsEachCamerasDetectionsTowardsIt) {
  const double offset = 0.02;  // m
  const double sigma = 0.003;  // m
  VisionEmulator emulator(profile(sigma, sigma), sizes());
  emulator_realism_t realism = ubersim::unchanged_realism();
  realism.object_position_offset = offset;
  ASSERT_EQ(emulator.apply_realism(realism), "");
  const Placed robot{0.1, 0.5};
  const Placed ball{-0.2, -0.4};
  std::map<int, Mean> robot_dx, robot_dy, ball_dx, ball_dy;
  for (const auto& f : run(emulator, 0, 2399, {robot}, ball)) {
    for (const auto& r : f.robots_yellow) {
      robot_dx[f.camera_id].add(r.x - robot.x);
      robot_dy[f.camera_id].add(r.y - robot.y);
    }
    for (const auto& b : f.balls) {
      ball_dx[f.camera_id].add(b.x - ball.x);
      ball_dy[f.camera_id].add(b.y - ball.y);
    }
  }
  // Camera 0 hangs at x = -1, camera 1 at x = +1: -2 cm and +2 cm in x.
  for (int camera : {0, 1}) {
    const double expected = camera == 0 ? -offset : offset;
    ASSERT_EQ(robot_dx[camera].n, 600);
    EXPECT_NEAR(robot_dx[camera].mean(), expected, 3 * robot_dx[camera].standard_error());
    EXPECT_NEAR(robot_dy[camera].mean(), 0, 3 * robot_dy[camera].standard_error());
    EXPECT_NEAR(ball_dx[camera].mean(), expected, 3 * ball_dx[camera].standard_error());
    EXPECT_NEAR(ball_dy[camera].mean(), 0, 3 * ball_dy[camera].standard_error());
    std::printf("object_position_offset %.3f m: camera %d robot shift %.2f mm, ball %.2f mm\n",
                offset, camera, 1e3 * robot_dx[camera].mean(), 1e3 * ball_dx[camera].mean());
  }
}

TEST(ErForceCameraModel, BallAreaIsThePinholeAreaWithTheConfiguredSpread) {
  VisionEmulator emulator(profile(0, 0), sizes());
  // Long lenses, so that the ball fills about 90 px^2 (noise of 6.5 px^2 then
  // never reaches an area of 0, where it would be cut off).
  const double focal = 1000;  // px
  auto camera_0 = straight_down(0, -1, 0, 4);
  auto camera_1 = straight_down(1, 1, 0, 4);
  camera_0.focal_length = camera_1.focal_length = focal;
  ASSERT_EQ(emulator.apply_cameras(camera_set({camera_0, camera_1})), "");
  const Placed ball{-1.4, 0.3};
  // Exact without noise: a ball of radius r at distance d under focal length f
  // fills pi f^2 r^2 / (d^2 - r^2) pixels.
  const Eigen::Vector3d camera(-1, 0, 4);
  const double d2 = (Eigen::Vector3d(ball.x, ball.y, kBallRadius) - camera).squaredNorm();
  const double pinhole =
      M_PI * focal * focal * kBallRadius * kBallRadius / (d2 - kBallRadius * kBallRadius);
  for (const auto& f : run(emulator, 0, 59, {}, ball)) {
    if (f.camera_id != 0) continue;
    ASSERT_EQ(f.balls.size(), 1u);
    EXPECT_NEAR(f.balls[0].area, pinhole, 1e-9);
  }
  const double sigma = 6.5;  // px^2, RC2021's stddev_ball_area
  emulator_realism_t realism = ubersim::unchanged_realism();
  realism.ball_area_sigma = sigma;
  ASSERT_EQ(emulator.apply_realism(realism), "");
  Mean area;
  for (const auto& f : run(emulator, 60, 12059, {}, ball)) {
    if (f.camera_id == 0) area.add(f.balls.at(0).area);
  }
  ASSERT_EQ(area.n, 3000);
  EXPECT_NEAR(area.sd(), sigma, 0.05 * sigma);
  EXPECT_NEAR(area.mean(), pinhole, 3 * area.standard_error());
  std::printf(
      "ball area: pinhole %.2f px^2; with stddev_ball_area %.1f: mean %.2f, sd %.3f "
      "(n %d)\n",
      pinhole, sigma, area.mean(), area.sd(), area.n);
}

TEST(ErForceCameraModel, DistortedCameraProjectsAndIntersectsConsistently) {
  using ubersim::vision::CameraIntrinsics;
  using ubersim::vision::PinholeCamera;
  const Eigen::Matrix3d down = ubersim::vision::overhead_rotation(Eigen::Vector3d::Zero());
  const PinholeCamera ideal(Eigen::Vector3d(0, 0, 6), down,
                            CameraIntrinsics{390, 300, 300, 0, 0, 0.0});
  const PinholeCamera distorted(Eigen::Vector3d(0, 0, 6), down,
                                CameraIntrinsics{390, 300, 300, 0, 0, 0.2});
  const Eigen::Vector3d point(3, 2, 0.15);
  const auto p_ideal = ideal.project(point);
  const auto p_distorted = distorted.project(point);
  ASSERT_TRUE(p_ideal && p_distorted);
  // SSL-Vision's model: undistorted radius = distorted radius x (1 + k rd^2).
  const Eigen::Vector2d u = (*p_ideal - Eigen::Vector2d(300, 300)) / 390;
  const Eigen::Vector2d d = (*p_distorted - Eigen::Vector2d(300, 300)) / 390;
  EXPECT_LT(d.norm(), u.norm());
  EXPECT_NEAR(d.norm() * (1 + 0.2 * d.squaredNorm()), u.norm(), 1e-12);
  const auto back = distorted.intersect_plane(*p_distorted, 0.15);
  ASSERT_TRUE(back);
  EXPECT_NEAR((*back - point).norm(), 0, 1e-9);
  // An image without edge takes every pixel; a negative distortion limits the radius.
  EXPECT_TRUE(distorted.in_image(Eigen::Vector2d(-1e4, 5e4)));
  const PinholeCamera barrel(Eigen::Vector3d(0, 0, 6), down,
                             CameraIntrinsics{390, 300, 300, 0, 0, -0.5});
  EXPECT_TRUE(barrel.project(Eigen::Vector3d(1, 0, 0)));
  EXPECT_FALSE(barrel.project(Eigen::Vector3d(30, 0, 0)));
}
