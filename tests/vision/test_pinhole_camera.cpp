// The pinhole camera model against hand-computed projections.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "ubersim/vision/pinhole_camera.hpp"

using Eigen::Vector2d;
using Eigen::Vector3d;
using ubersim::vision::CameraIntrinsics;
using ubersim::vision::overhead_rotation;
using ubersim::vision::PinholeCamera;

namespace {

const CameraIntrinsics kIntrinsics{500.0, 320.0, 240.0, 640, 480};
constexpr double kDeg = M_PI / 180.0;

PinholeCamera straight_down(const Vector3d& position) {
  return PinholeCamera(position, overhead_rotation(Vector3d::Zero()), kIntrinsics);
}

}  // namespace

TEST(PinholeCamera, StraightDownImageIsAMapOfTheField) {
  const PinholeCamera camera = straight_down(Vector3d(1, 2, 4));
  // 0.5 m along +x and 0.2 m along +y of the nadir, 4 m below: columns grow with
  // x, rows shrink with y (the image shows +y up).
  const auto pixel = camera.project(Vector3d(1.5, 2.2, 0));
  ASSERT_TRUE(pixel);
  EXPECT_NEAR(pixel->x(), 320 + 500 * 0.5 / 4, 1e-9);
  EXPECT_NEAR(pixel->y(), 240 - 500 * 0.2 / 4, 1e-9);
  // A point 1 m up is 3 m from the camera: it lands farther from the centre.
  const auto raised = camera.project(Vector3d(1.5, 2.2, 1));
  EXPECT_NEAR(raised->x(), 320 + 500 * 0.5 / 3, 1e-9);
}

TEST(PinholeCamera, YawTurnsTheImageOnTheField) {
  const PinholeCamera camera(Vector3d(0, 0, 4), overhead_rotation(Vector3d(0, 0, 90 * kDeg)),
                             kIntrinsics);
  // Yawed 90 deg, image columns run along field +y.
  const auto pixel = camera.project(Vector3d(0, 0.4, 0));
  EXPECT_NEAR(pixel->x(), 320 + 500 * 0.4 / 4, 1e-9);
  EXPECT_NEAR(pixel->y(), 240, 1e-9);
}

TEST(PinholeCamera, RayThroughAPixelMeetsThePlaneAtThePoint) {
  const PinholeCamera camera(Vector3d(-1, 0.5, 3.5),
                             overhead_rotation(Vector3d(8 * kDeg, -12 * kDeg, 33 * kDeg)),
                             kIntrinsics);
  for (const Vector3d& point : {Vector3d(-1, 0.5, 0), Vector3d(0.3, -0.4, 0.15),
                                Vector3d(-2.2, 1.1, 0.0215), Vector3d(-0.5, 0.9, 1.2)}) {
    const auto pixel = camera.project(point);
    ASSERT_TRUE(pixel);
    const auto back = camera.intersect_plane(*pixel, point.z());
    ASSERT_TRUE(back);
    EXPECT_LT((*back - point).norm(), 1e-9) << point.transpose();
  }
}

TEST(PinholeCamera, ImageBoundsAndImpossibleRays) {
  const PinholeCamera camera = straight_down(Vector3d(0, 0, 4));
  EXPECT_TRUE(camera.in_image(Vector2d(0, 0)));
  EXPECT_TRUE(camera.in_image(Vector2d(639.9, 479.9)));
  EXPECT_FALSE(camera.in_image(Vector2d(640, 10)));
  EXPECT_FALSE(camera.in_image(Vector2d(10, -0.1)));
  // Above the camera is behind it.
  EXPECT_FALSE(camera.project(Vector3d(0, 0, 5)));
  // A plane above the camera is never reached by a ray going down.
  EXPECT_FALSE(camera.intersect_plane(Vector2d(320, 240), 5.0));
}

TEST(PinholeCamera, CalibrationMessageDescribesTheCamera) {
  const PinholeCamera camera = straight_down(Vector3d(1, 2, 4));
  const auto c = camera.to_calibration(3);
  EXPECT_EQ(c.camera_id, 3);
  EXPECT_EQ(c.image_width, 640);
  EXPECT_DOUBLE_EQ(c.focal_length, 500);
  EXPECT_DOUBLE_EQ(c.position[2], 4);
  // Straight down is half a turn about field x: w = 0, x = 1.
  EXPECT_NEAR(c.orientation[0], 0, 1e-12);
  EXPECT_NEAR(std::abs(c.orientation[1]), 1, 1e-12);
  // The quaternion rebuilds the rotation.
  const Eigen::Quaterniond q(c.orientation[0], c.orientation[1], c.orientation[2],
                             c.orientation[3]);
  EXPECT_TRUE(q.toRotationMatrix().isApprox(camera.camera_to_field(), 1e-12));
}
