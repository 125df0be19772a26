// RealismConfig (ER-Force's RealismConfigErForce inside Any) -> the
// emulators' run-time realism message, in-process.
#include <gtest/gtest.h>
#include <ssl_simulation_custom_erforce_realism.pb.h>

#include <cctype>

#include "erforce_presets.hpp"
#include "ubersim/ssl_bridge/realism_translation.hpp"
#include "ubersim/radio/radio_profile.hpp"
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
  // What the model has no place for is named, once.
  ASSERT_EQ(out.errors.size(), 1u);
  for (const char* field :
       {"stddev_ball_area", "camera_overlap", "camera_position_error", "object_position_offset"}) {
    EXPECT_TRUE(mentions(out.errors, kErrorUnsupported, field)) << field;
  }
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
    const auto radio = radio::load_radio_profile(dir, "erforce_" + file);
    EXPECT_NEAR(radio.command.latency, r.command_latency, 1e-9) << preset;
    EXPECT_NEAR(radio.command.robot_loss, r.command_robot_loss, 1e-7) << preset;
    EXPECT_NEAR(radio.feedback.robot_loss, r.feedback_robot_loss, 1e-7) << preset;
  }
}
