// SimulatorConfig.geometry.calib -> the vision emulator's cameras
// (vision_cameras_t), in-process: the official simulation controller's
// Division A geometry, rotations that are and are not usable, invalid values.
#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <fstream>
#include <sstream>

#include "ubersim/ssl_bridge/calibration_translation.hpp"
#include "ubersim/ssl_bridge/sim_control_translation.hpp"
#include "ubersim/ssl_bridge/vision_translation.hpp"
#include "ubersim/vision/vision_emulator.hpp"

using namespace ubersim;
using namespace ubersim::ssl;

namespace {

SSL_GeometryData official_division_a() {
  std::ifstream file(UBERSIM_OFFICIAL_GEOMETRY_DIV_A);
  std::stringstream text;
  text << file.rdbuf();
  SSL_GeometryData geometry;
  EXPECT_TRUE(google::protobuf::TextFormat::ParseFromString(text.str(), &geometry));
  return geometry;
}

bool mentions(const Errors& errors, const std::string& code, const std::string& text) {
  for (const auto& e : errors) {
    if (e.code() == code && e.message().find(text) != std::string::npos) return true;
  }
  return false;
}

Eigen::Quaterniond orientation(const camera_calibration_t& c) {
  return Eigen::Quaterniond(c.orientation[0], c.orientation[1], c.orientation[2], c.orientation[3]);
}

}  // namespace

TEST(SslCalibration, OfficialDivisionAGeometryBecomesTwoCamerasWithoutAnError) {
  const SSL_GeometryData geometry = official_division_a();
  ASSERT_EQ(geometry.calib_size(), 2);
  const CalibrationTranslation out = translate_calibrations(geometry);
  EXPECT_TRUE(out.errors.empty());
  ASSERT_TRUE(out.cameras.has_value());
  ASSERT_EQ(out.cameras->num_cameras, 2);
  for (int k = 0; k < 2; ++k) {
    const camera_calibration_t& c = out.cameras->cameras[static_cast<std::size_t>(k)];
    EXPECT_EQ(c.camera_id, k);
    // At derived_camera_world_t*, as the ER-Force simulator places them.
    EXPECT_NEAR(c.position[0], k == 0 ? -3.01 : 3.01, 1e-9);
    EXPECT_NEAR(c.position[1], 0, 1e-9);
    EXPECT_NEAR(c.position[2], 6, 1e-9);
    EXPECT_DOUBLE_EQ(c.focal_length, 390);
    EXPECT_DOUBLE_EQ(c.principal_x, 300);
    EXPECT_DOUBLE_EQ(c.principal_y, 300);
    EXPECT_NEAR(c.distortion, 0.2, 1e-7);
    EXPECT_EQ(c.image_width, 0);  // no image size given: the regions decide
    EXPECT_EQ(c.image_height, 0);
    // q = 0.7, 0.7, 0.7, 0.7 is not a rotation: straight down.
    const Eigen::Vector3d axis = orientation(c).toRotationMatrix() * Eigen::Vector3d::UnitZ();
    EXPECT_NEAR(axis.z(), -1, 1e-12);
  }
  // The vision emulator takes them as they are.
  vision::VisionProfile profile = vision::load_vision_profile(UBERSIM_SOURCE_CONFIG_DIR, "modern");
  vision::VisionEmulator emulator(profile,
                                  vision::RobotSizes::from_config_dir(UBERSIM_SOURCE_CONFIG_DIR));
  EXPECT_EQ(emulator.apply_cameras(*out.cameras), "");
  EXPECT_EQ(emulator.camera_count(), 2u);

  // Through the whole simulation command too, and a geometry without calibrations keeps them.
  SimulatorCommand command;
  *command.mutable_config()->mutable_geometry() = geometry;
  SimControlTranslation translated = translate_simulator_command(command, nullptr, {});
  ASSERT_TRUE(translated.cameras.has_value());
  EXPECT_EQ(translated.cameras->num_cameras, 2);
  for (const auto& error : translated.errors) {
    EXPECT_EQ(error.message().find("calib"), std::string::npos) << error.message();
  }
  command.mutable_config()->mutable_geometry()->clear_calib();
  translated = translate_simulator_command(command, nullptr, {});
  EXPECT_FALSE(translated.cameras.has_value());
}

TEST(SslCalibration, AUsableRotationIsKeptAndPositionComesFromTheExtrinsicsWhenNotDerived) {
  // A tilted camera as ubersim itself reports it (VISION_GEOMETRY -> SSL).
  const Eigen::Matrix3d camera_to_field =
      vision::overhead_rotation(Eigen::Vector3d(5 * M_PI / 180, -3 * M_PI / 180, 30 * M_PI / 180));
  vision::PinholeCamera camera(Eigen::Vector3d(1.5, -2.0, 4.5), camera_to_field,
                               vision::CameraIntrinsics{650, 390, 290, 780, 580, -0.1});
  vision_geometry_t ours{};
  ours.cameras.push_back(camera.to_calibration(4));
  ours.num_cameras = 1;
  SSL_GeometryData geometry = geometry_packet(ours, {}).geometry();
  ASSERT_EQ(geometry.calib_size(), 1);

  for (bool derived : {true, false}) {
    if (!derived) {
      geometry.mutable_calib(0)->clear_derived_camera_world_tx();
      geometry.mutable_calib(0)->clear_derived_camera_world_ty();
      geometry.mutable_calib(0)->clear_derived_camera_world_tz();
    }
    const CalibrationTranslation out = translate_calibrations(geometry);
    ASSERT_TRUE(out.errors.empty()) << out.errors.front().message();
    ASSERT_TRUE(out.cameras.has_value());
    const camera_calibration_t& c = out.cameras->cameras.at(0);
    EXPECT_EQ(c.camera_id, 4);
    EXPECT_NEAR(c.position[0], 1.5, 1e-3);  // float millimetres
    EXPECT_NEAR(c.position[1], -2.0, 1e-3);
    EXPECT_NEAR(c.position[2], 4.5, 1e-3);
    EXPECT_LT(orientation(c).angularDistance(Eigen::Quaterniond(camera_to_field)), 1e-5);
    EXPECT_EQ(c.image_width, 780);
    EXPECT_EQ(c.image_height, 580);
    EXPECT_NEAR(c.distortion, -0.1, 1e-7);
  }

  // A rotation that puts the camera elsewhere than its derived position is not this camera's.
  SSL_GeometryData moved = geometry_packet(ours, {}).geometry();
  moved.mutable_calib(0)->set_derived_camera_world_tx(-1500);
  const CalibrationTranslation out = translate_calibrations(moved);
  ASSERT_TRUE(out.cameras.has_value());
  EXPECT_NEAR(out.cameras->cameras[0].position[0], -1.5, 1e-6);
  EXPECT_NEAR(
      (orientation(out.cameras->cameras[0]).toRotationMatrix() * Eigen::Vector3d::UnitZ()).z(), -1,
      1e-12);
}

TEST(SslCalibration, InvalidCalibrationsAreNamedAndNoCameraChanges) {
  const SSL_GeometryData official = official_division_a();
  const auto refused = [](const SSL_GeometryData& geometry, const std::string& text) {
    const CalibrationTranslation out = translate_calibrations(geometry);
    EXPECT_FALSE(out.cameras.has_value()) << text;
    EXPECT_TRUE(mentions(out.errors, kErrorInvalid, text)) << text;
  };
  SSL_GeometryData g = official;
  g.mutable_calib(1)->set_focal_length(NAN);
  refused(g, "calib[1]: not valid: focal_length");
  g = official;
  g.mutable_calib(0)->set_distortion(INFINITY);
  refused(g, "distortion");
  g = official;
  g.mutable_calib(0)->clear_derived_camera_world_ty();
  refused(g, "only some set");
  g = official;
  for (int k = 0; k < 2; ++k) {
    g.mutable_calib(k)->clear_derived_camera_world_tx();
    g.mutable_calib(k)->clear_derived_camera_world_ty();
    g.mutable_calib(k)->clear_derived_camera_world_tz();
  }
  refused(g, "no camera position");  // and q is no rotation to take it from
  g = official;
  g.mutable_calib(1)->set_camera_id(0);
  refused(g, "used twice");
  g = official;
  g.mutable_calib(0)->set_derived_camera_world_tz(200);  // 0.2 m: below every robot
  refused(g, "camera position");
  g = official;
  g.mutable_calib(0)->set_camera_id(1000);
  refused(g, "camera_id");
  g = official;
  for (int k = 0; k < 63; ++k) *g.add_calib() = official.calib(0);
  refused(g, "at most 64");
  g = official;
  g.clear_calib();
  const CalibrationTranslation none = translate_calibrations(g);
  EXPECT_FALSE(none.cameras.has_value());
  EXPECT_TRUE(none.errors.empty());
}
