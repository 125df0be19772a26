// RealismConfig (ER-Force's RealismConfigErForce inside Any) -> the
// emulators' run-time realism message, in-process.
#include <gtest/gtest.h>
#include <ssl_simulation_custom_erforce_realism.pb.h>

#include <cctype>
#include <cmath>

#include "erforce_presets.hpp"
#include "ubersim/radio/radio_profile.hpp"
#include "ubersim/ssl_bridge/realism_translation.hpp"
#include "ubersim/vision/vision_profile.hpp"

using namespace ubersim;
using namespace ubersim::ssl;

namespace {

bool mentions(const Errors& errors, const std::string& code, const std::string& text) {
  for (const auto& e : errors) {
    if (e.code() == code && e.message().find(text) != std::string::npos) return true;
  }
  return false;
}

}  // namespace

TEST(SslRealism, ErForceFieldsMapOntoTheEmulatorParameters) {
  RealismConfig config;
  config.add_custom()->PackFrom(ssl_test::erforce_preset("Realistic"));
  const RealismTranslation out = translate_realism(config);
  ASSERT_TRUE(out.realism.has_value());
  const emulator_realism_t& r = *out.realism;
  EXPECT_NEAR(r.ball_sigma_position, 0.0014, 1e-7);
  EXPECT_NEAR(r.robot_sigma_position, 0.0013, 1e-7);
  EXPECT_NEAR(r.robot_sigma_orientation, 0.01, 1e-7);
  EXPECT_NEAR(r.ball_min_visible_fraction, 0.4, 1e-7);
  EXPECT_NEAR(r.false_ball_rate, 0.05, 1e-7);
  EXPECT_NEAR(r.command_robot_loss, 0.03, 1e-7);
  EXPECT_NEAR(r.feedback_robot_loss, 0.1, 1e-7);
  EXPECT_NEAR(r.ball_detection_probability, 0.95, 1e-7);
  EXPECT_NEAR(r.robot_detection_probability, 0.98, 1e-7);
  EXPECT_DOUBLE_EQ(r.vision_latency, 0.035);
  EXPECT_DOUBLE_EQ(r.vision_processing_time, 0.010);
  EXPECT_DOUBLE_EQ(r.command_latency, 0.003);
  // ER-Force's camera model (docs/vision.md).
  EXPECT_NEAR(r.ball_area_sigma, 6.5, 1e-7);
  EXPECT_NEAR(r.camera_overlap, 1, 1e-7);
  EXPECT_NEAR(r.camera_position_error, 0.1, 1e-7);
  EXPECT_NEAR(r.object_position_offset, 0.02, 1e-7);
  EXPECT_TRUE(out.errors.empty());  // every field of the preset is modelled
}

// Every field of every ER-Force preset is modelled: no error names one
// (simulate_dribbling = false, RC2021's, is physics' and not the emulators').
TEST(SslRealism, EveryErForcePresetTranslatesWithoutAnErrorOnItsFields) {
  for (const std::string preset : {"None", "Friendly", "RC2021", "Realistic"}) {
    RealismConfig config;
    config.add_custom()->PackFrom(ssl_test::erforce_preset(preset));
    const RealismTranslation out = translate_realism(config);
    ASSERT_TRUE(out.realism.has_value()) << preset;
    const emulator_realism_t& r = *out.realism;
    for (double v :
         {r.ball_area_sigma, r.camera_overlap, r.camera_position_error, r.object_position_offset}) {
      EXPECT_GE(v, 0) << preset;  // set, not "unchanged"
    }
    for (const auto& error : out.errors) {
      std::string message = error.message();
      const auto dribbling = message.find("simulate_dribbling");
      if (dribbling != std::string::npos) message.erase(dribbling);  // the other engineer's part
      for (const char* field :
           {"stddev", "camera", "object_position_offset", "missing", "vision", "dribbler_ball",
            "command", "response", "invisible", "visibility"}) {
        EXPECT_EQ(message.find(field), std::string::npos) << preset << ": " << error.message();
      }
    }
  }
}

TEST(SslRealism, CameraModelValuesOutsideTheEmulatorsBoundsAreNamed) {
  RealismConfigErForce erforce;
  erforce.set_camera_overlap(-1);
  erforce.set_camera_position_error(20);  // m: beyond 10 m
  erforce.set_object_position_offset(NAN);
  erforce.set_stddev_ball_area(2e6);  // px^2: beyond 1e6
  RealismConfig config;
  config.add_custom()->PackFrom(erforce);
  const RealismTranslation out = translate_realism(config);
  ASSERT_TRUE(out.realism.has_value());
  for (const char* field :
       {"camera_overlap", "camera_position_error", "object_position_offset", "stddev_ball_area"}) {
    EXPECT_TRUE(mentions(out.errors, kErrorInvalid, field)) << field;
  }
  EXPECT_LT(out.realism->camera_overlap, 0);  // unchanged
  EXPECT_LT(out.realism->camera_position_error, 0);
  EXPECT_LT(out.realism->object_position_offset, 0);
  EXPECT_LT(out.realism->ball_area_sigma, 0);
  // The bridge's bounds are the vision emulator's.
  EXPECT_EQ(vision::kMaxCameraOffset, 10.0);
  EXPECT_EQ(vision::kMaxCameraOverlap, 1000.0);
  EXPECT_EQ(vision::kMaxBallAreaSigma, 1e6);
}

TEST(SslRealism, UnsetFieldsStayUnchangedAndBadValuesAreNamed) {
  RealismConfigErForce partial;
  partial.set_stddev_robot_p(0.002f);
  partial.set_missing_ball_detections(1.5f);  // not a probability
  partial.set_enable_invisible_ball(false);
  RealismConfig config;
  config.add_custom()->PackFrom(partial);
  google::protobuf::Any other;
  other.set_type_url("type.googleapis.com/grsim.Noise");
  *config.add_custom() = other;
  const RealismTranslation out = translate_realism(config);
  ASSERT_TRUE(out.realism.has_value());
  EXPECT_NEAR(out.realism->robot_sigma_position, 0.002, 1e-7);
  EXPECT_LT(out.realism->ball_sigma_position, 0);  // unchanged
  EXPECT_LT(out.realism->vision_latency, 0);
  EXPECT_LT(out.realism->ball_detection_probability, 0);
  EXPECT_DOUBLE_EQ(out.realism->ball_min_visible_fraction, 0);  // always visible
  EXPECT_TRUE(mentions(out.errors, kErrorInvalid, "missing_ball_detections"));
  EXPECT_TRUE(mentions(out.errors, kErrorUnsupported, "realism_config.custom[1]"));
  EXPECT_TRUE(mentions(out.errors, kErrorUnsupported, "grsim.Noise"));
}

// The shipped profile files carry what the bridge sends for the same preset.
TEST(SslRealism, ShippedPresetProfilesHoldTheValuesThePresetsMapTo) {
  const std::string dir = UBERSIM_SOURCE_CONFIG_DIR;
  for (const std::string preset : {"None", "Friendly", "RC2021", "Realistic"}) {
    RealismConfig config;
    config.add_custom()->PackFrom(ssl_test::erforce_preset(preset));
    const RealismTranslation out = translate_realism(config);
    ASSERT_TRUE(out.realism.has_value());
    const emulator_realism_t& r = *out.realism;
    std::string file = preset;
    for (char& c : file) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    const auto vision = vision::load_vision_profile(dir, "erforce_" + file);
    EXPECT_NEAR(vision.robot_sigma_x, r.robot_sigma_position, 1e-7) << preset;
    EXPECT_NEAR(vision.robot_sigma_y, r.robot_sigma_position, 1e-7) << preset;
    EXPECT_NEAR(vision.robot_sigma_orientation, r.robot_sigma_orientation, 1e-7) << preset;
    EXPECT_NEAR(vision.ball_sigma_x, r.ball_sigma_position, 1e-7) << preset;
    EXPECT_NEAR(vision.robot_detection_probability, r.robot_detection_probability, 1e-7);
    EXPECT_NEAR(vision.ball_detection_probability, r.ball_detection_probability, 1e-7);
    EXPECT_NEAR(vision.false_ball_rate, r.false_ball_rate, 1e-7) << preset;
    EXPECT_NEAR(vision.ball_min_visible_fraction, r.ball_min_visible_fraction, 1e-7);
    EXPECT_NEAR(vision.latency, r.vision_latency, 1e-9) << preset;
    EXPECT_NEAR(vision.processing_time, r.vision_processing_time, 1e-9) << preset;
    EXPECT_NEAR(vision.ball_area_sigma, r.ball_area_sigma, 1e-7) << preset;
    EXPECT_NEAR(vision.camera_overlap, r.camera_overlap, 1e-7) << preset;
    EXPECT_NEAR(vision.camera_position_error, r.camera_position_error, 1e-7) << preset;
    EXPECT_NEAR(vision.object_position_offset, r.object_position_offset, 1e-7) << preset;
    for (const auto& camera : vision.cameras) {  // ER-Force has no other calibration error
      EXPECT_EQ(camera.position_error.norm(), 0) << preset;
      EXPECT_EQ(camera.roll_pitch_yaw_error.norm(), 0) << preset;
      EXPECT_EQ(camera.focal_length_error, 0) << preset;
    }
    const auto radio = radio::load_radio_profile(dir, "erforce_" + file);
    EXPECT_NEAR(radio.command.latency, r.command_latency, 1e-9) << preset;
    EXPECT_NEAR(radio.command.robot_loss, r.command_robot_loss, 1e-7) << preset;
    EXPECT_NEAR(radio.feedback.robot_loss, r.feedback_robot_loss, 1e-7) << preset;
  }
}
