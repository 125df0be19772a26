// VISION / VISION_GEOMETRY -> SSL wrapper packets, in-process.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>

#include "ubersim/ssl_bridge/vision_translation.hpp"

using namespace ubersim;
using namespace ubersim::ssl;

TEST(SslVisionTranslation, FrameNumberWrapsLikeUint32AndEmptyFrameIsValid) {
  vision_frame_t frame{};
  frame.camera_id = 3;
  frame.frame_number = (int64_t{1} << 32) + 5;
  frame.t_capture = 12.5;
  frame.t_sent = 12.6;
  const SSL_WrapperPacket packet = detection_packet(frame);
  ASSERT_TRUE(packet.has_detection());
  EXPECT_FALSE(packet.has_geometry());
  EXPECT_EQ(packet.detection().frame_number(), 5u);
  EXPECT_EQ(packet.detection().camera_id(), 3u);
  EXPECT_DOUBLE_EQ(packet.detection().t_capture(), 12.5);
  EXPECT_DOUBLE_EQ(packet.detection().t_sent(), 12.6);
  EXPECT_EQ(packet.source(), SSL_SOURCE_OTHER);
  EXPECT_TRUE(packet.IsInitialized());
}

TEST(SslVisionTranslation, RobotInMillimetresWithOrientationInRadians) {
  vision_frame_t frame{};
  vision_robot_t robot{};
  robot.robot_id = 7;
  robot.confidence = 0.75f;
  robot.x = -1.25;
  robot.y = 0.5;
  robot.orientation = -2.0;
  robot.pixel_x = 320.5;
  robot.pixel_y = 240.25;
  frame.robots_blue.push_back(robot);
  frame.num_robots_blue = 1;
  const SSL_WrapperPacket packet = detection_packet(frame);
  const auto& out = packet.detection();
  ASSERT_EQ(out.robots_blue_size(), 1);
  EXPECT_EQ(out.robots_yellow_size(), 0);
  EXPECT_EQ(out.robots_blue(0).robot_id(), 7u);
  EXPECT_FLOAT_EQ(out.robots_blue(0).confidence(), 0.75f);
  EXPECT_FLOAT_EQ(out.robots_blue(0).x(), -1250.0f);
  EXPECT_FLOAT_EQ(out.robots_blue(0).y(), 500.0f);
  EXPECT_FLOAT_EQ(out.robots_blue(0).orientation(), -2.0f);
  EXPECT_FLOAT_EQ(out.robots_blue(0).pixel_x(), 320.5f);
  EXPECT_FLOAT_EQ(out.robots_blue(0).pixel_y(), 240.25f);
}

// Anyone on the bus may send VISION; NaN or a number too large for SSL's
// float millimetres must not reach SSL software (the bridge drops the frame).
TEST(SslVisionTranslation, AFrameWithANumberNotFiniteOrHugeIsNotForwarded) {
  vision_frame_t frame{};
  frame.robots_blue.push_back(vision_robot_t{});
  frame.balls.push_back(vision_ball_t{});
  EXPECT_TRUE(forwardable(frame));
  vision_frame_t bad = frame;
  bad.robots_blue[0].orientation = std::nan("");
  EXPECT_FALSE(forwardable(bad));
  bad = frame;
  bad.balls[0].x = 1e300;  // finite, but infinite as float mm
  EXPECT_FALSE(forwardable(bad));
  EXPECT_TRUE(std::isinf(detection_packet(bad).detection().balls(0).x()))
      << "what would have gone out";
  bad = frame;
  bad.t_capture = -std::numeric_limits<double>::infinity();
  EXPECT_FALSE(forwardable(bad));
}

namespace {

vision_geometry_t division_b_like() {
  vision_geometry_t g{};
  g.field.field_length = 9.0;
  g.field.field_width = 6.0;
  g.field.boundary_width = 0.3;
  g.field.line_width = 0.01;
  g.field.goal_width = 1.0;
  g.field.goal_depth = 0.18;
  g.field.goal_height = 0.155;
  g.field.center_circle_radius = 0.5;
  g.field.penalty_area_depth = 1.0;
  g.field.penalty_area_width = 2.0;
  g.field.ball_radius = 0.0215;
  g.field.penalty_mark_distance = 6.0;
  g.field.boundary_width_goal_line = 0.6;       // more room behind the goal lines (2026)
  g.field.goal_substitution_area_width = 0.25;  // not the SSL default: read from the field
  camera_calibration_t camera{};
  camera.camera_id = 1;
  camera.focal_length = 500;
  camera.principal_x = 390;
  camera.principal_y = 290;
  camera.image_width = 780;
  camera.image_height = 580;
  camera.position[0] = 2.25;
  camera.position[1] = -1.0;
  camera.position[2] = 4.0;
  // Camera -> field: 180 degrees about x (looking straight down).
  camera.orientation[0] = 0;
  camera.orientation[1] = 1;
  camera.orientation[2] = 0;
  camera.orientation[3] = 0;
  g.cameras.push_back(camera);
  g.num_cameras = 1;
  return g;
}

}  // namespace

TEST(SslVisionTranslation, AGeometryWithANumberNotFiniteOrOutOfRangeIsNotForwarded) {
  const vision_geometry_t good = division_b_like();
  EXPECT_TRUE(forwardable(good));
  vision_geometry_t bad = good;
  bad.field.ball_radius = std::nan("");
  EXPECT_FALSE(forwardable(bad));
  EXPECT_TRUE(std::isnan(geometry_packet(bad, {}).geometry().field().ball_radius()))
      << "what would have gone out";
  bad = good;
  bad.field.field_length = 1e7;  // 1e10 mm: not an int32 of whole millimetres
  EXPECT_FALSE(forwardable(bad));
  bad = good;
  bad.field.goal_width = -1.0;
  EXPECT_FALSE(forwardable(bad));
  bad = good;
  bad.cameras[0].position[2] = 1e300;  // infinite as float mm
  EXPECT_FALSE(forwardable(bad));
  EXPECT_TRUE(std::isinf(geometry_packet(bad, {}).geometry().calib(0).derived_camera_world_tz()));
  bad = good;
  bad.cameras[0].orientation[0] = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(forwardable(bad));
  bad = good;
  bad.cameras[0].focal_length = -std::numeric_limits<double>::infinity();
  EXPECT_FALSE(forwardable(bad));
  bad = good;
  bad.cameras[0].image_width = -1;  // 4294967295 px as SSL's uint32
  EXPECT_FALSE(forwardable(bad));
  // The largest numbers let through stay finite in the packet.
  vision_geometry_t large = good;
  large.field.field_length = 1e6;
  for (double& v : large.cameras[0].position) v = 1e9;
  for (double& v : large.cameras[0].orientation) v = -1e9;
  large.cameras[0].focal_length = 1e9;
  ASSERT_TRUE(forwardable(large));
  const SSL_WrapperPacket packet = geometry_packet(large, {});
  EXPECT_EQ(packet.geometry().field().field_length(), 1'000'000'000);
  const auto& c = packet.geometry().calib(0);
  for (float v : {c.tx(), c.ty(), c.tz(), c.derived_camera_world_tx(), c.q0(), c.focal_length()}) {
    EXPECT_TRUE(std::isfinite(v));
  }
}

TEST(SslVisionTranslation, GeometryFieldInWholeMillimetresWithMarkings) {
  GeometryExtras extras;
  extras.max_robot_radius = 0.09;
  extras.ball_model = BallModel{3.6, 0.3, 0.7};
  const SSL_WrapperPacket packet = geometry_packet(division_b_like(), extras);
  ASSERT_TRUE(packet.IsInitialized());
  const auto& field = packet.geometry().field();
  EXPECT_EQ(field.field_length(), 9000);
  EXPECT_EQ(field.field_width(), 6000);
  EXPECT_EQ(field.goal_width(), 1000);
  EXPECT_EQ(field.goal_depth(), 180);
  EXPECT_EQ(field.boundary_width(), 300);
  EXPECT_EQ(field.boundary_width_goal_line(), 600);
  EXPECT_EQ(field.goal_substitution_area_width(), 250);
  EXPECT_EQ(packet.source(), SSL_SOURCE_OTHER);
  EXPECT_EQ(field.penalty_area_depth(), 1000);
  EXPECT_EQ(field.penalty_area_width(), 2000);
  EXPECT_EQ(field.center_circle_radius(), 500);
  EXPECT_EQ(field.line_thickness(), 10);
  EXPECT_EQ(field.goal_center_to_penalty_mark(), 6000);
  EXPECT_EQ(field.goal_height(), 155);
  EXPECT_FLOAT_EQ(field.ball_radius(), 21.5f);
  EXPECT_FLOAT_EQ(field.max_robot_radius(), 90.0f);
  ASSERT_EQ(field.field_lines_size(), 12);
  ASSERT_EQ(field.field_arcs_size(), 1);
  EXPECT_EQ(field.field_arcs(0).type(), CenterCircle);
  EXPECT_FLOAT_EQ(field.field_arcs(0).radius(), 500.0f);
  for (const auto& line : field.field_lines()) {
    if (line.type() == TopTouchLine) {
      EXPECT_FLOAT_EQ(line.p1().x(), -4500.0f);
      EXPECT_FLOAT_EQ(line.p1().y(), 3000.0f);
      EXPECT_FLOAT_EQ(line.p2().x(), 4500.0f);
      EXPECT_FLOAT_EQ(line.thickness(), 10.0f);
    }
    if (line.type() == RightPenaltyStretch) {
      EXPECT_FLOAT_EQ(line.p1().x(), 3500.0f);
      EXPECT_FLOAT_EQ(std::abs(line.p1().y()), 1000.0f);
    }
  }
  const auto& model = packet.geometry().models().straight_two_phase();
  EXPECT_DOUBLE_EQ(model.acc_slide(), -3.6);
  EXPECT_DOUBLE_EQ(model.acc_roll(), -0.3);
  EXPECT_DOUBLE_EQ(model.k_switch(), 0.7);
}

TEST(SslVisionTranslation, CalibrationIsWorldToCameraInMillimetres) {
  const SSL_WrapperPacket packet = geometry_packet(division_b_like(), {});
  EXPECT_FALSE(packet.geometry().has_models());
  ASSERT_EQ(packet.geometry().calib_size(), 1);
  const auto& c = packet.geometry().calib(0);
  EXPECT_EQ(c.camera_id(), 1u);
  EXPECT_FLOAT_EQ(c.focal_length(), 500.0f);
  EXPECT_FLOAT_EQ(c.principal_point_x(), 390.0f);
  EXPECT_EQ(c.pixel_image_width(), 780u);
  EXPECT_FLOAT_EQ(c.derived_camera_world_tx(), 2250.0f);
  EXPECT_FLOAT_EQ(c.derived_camera_world_ty(), -1000.0f);
  EXPECT_FLOAT_EQ(c.derived_camera_world_tz(), 4000.0f);
  // The camera centre must map to the camera origin: R(q) C + t = 0, with
  // q = (q0, q1, q2) vector part and q3 scalar part.
  const double w = c.q3(), x = c.q0(), y = c.q1(), z = c.q2();
  const std::array<double, 3> centre{2250, -1000, 4000};
  const double R[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                          {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                          {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
  const std::array<double, 3> t{c.tx(), c.ty(), c.tz()};
  for (int i = 0; i < 3; ++i) {
    const double mapped =
        R[i][0] * centre[0] + R[i][1] * centre[1] + R[i][2] * centre[2] + t[static_cast<size_t>(i)];
    EXPECT_NEAR(mapped, 0.0, 1e-3) << "row " << i;
  }
  // Looking straight down: a point 4 m below the camera is 4000 mm along the
  // camera's z axis (camera z = optical axis, as in our camera model).
  const std::array<double, 3> below{2250, -1000, 0};
  double along_z = t[2];
  for (int j = 0; j < 3; ++j) along_z += R[2][j] * below[static_cast<size_t>(j)];
  EXPECT_NEAR(along_z, 4000.0, 1e-2);
}

TEST(SslVisionTranslation, BallAreaInWholePixelsDistortionAndAnImageWithoutEdge) {
  vision_frame_t frame{};
  vision_ball_t ball{};
  ball.area = 71.6;
  frame.balls.push_back(ball);
  ball.area = 0;  // not measured
  frame.balls.push_back(ball);
  frame.num_balls = 2;
  const SSL_WrapperPacket detection = detection_packet(frame);
  ASSERT_EQ(detection.detection().balls_size(), 2);
  EXPECT_EQ(detection.detection().balls(0).area(), 72u);
  EXPECT_FALSE(detection.detection().balls(1).has_area());
  frame.balls[0].area = std::nan("");
  EXPECT_FALSE(forwardable(frame));

  vision_geometry_t geometry = division_b_like();
  geometry.cameras[0].distortion = 0.2;
  geometry.cameras[0].image_width = geometry.cameras[0].image_height = 0;  // no edge
  const auto& c = geometry_packet(geometry, {}).geometry().calib(0);
  EXPECT_FLOAT_EQ(c.distortion(), 0.2f);
  EXPECT_FALSE(c.has_pixel_image_width());
  EXPECT_FALSE(c.has_pixel_image_height());
  geometry.cameras[0].distortion = INFINITY;
  EXPECT_FALSE(forwardable(geometry));
}
