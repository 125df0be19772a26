// Emulator profiles: the shipped ones load with the values the issue asks
// for, every key carries a unit comment, and mistakes are errors naming file
// and line.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <regex>

#include "ubersim/config.hpp"
#include "ubersim/vision/vision_profile.hpp"

using ubersim::ConfigError;
using ubersim::ConfigFile;
using ubersim::vision::load_vision_profile;
using ubersim::vision::VisionProfile;

namespace {

const std::string kConfigDir = UBERSIM_SOURCE_CONFIG_DIR;

std::string minimal_profile() {
  return R"(SEED = 7
FRAME_RATE = 60
LATENCY = 0.05
LATENCY_JITTER = 0
PROCESSING_TIME = 0.01
GEOMETRY_PERIOD = 1
ROBOT_SIGMA_X = 0.01
ROBOT_SIGMA_Y = 0.02
ROBOT_SIGMA_ORIENTATION = 0.03
BALL_SIGMA_X = 0.04
BALL_SIGMA_Y = 0.05
ROBOT_DETECTION_PROBABILITY = 0.9
BALL_DETECTION_PROBABILITY = 0.8
ROBOT_CONFIDENCE = 0.7
BALL_CONFIDENCE = 0.6
CONFIDENCE_SIGMA = 0.1
FALSE_BALL_RATE = 0.5
FALSE_BALL_SPREAD = 0.02
FALSE_BALL_CONFIDENCE = 0.2
BALL_MIN_VISIBLE_FRACTION = 0.4
BALL_RADIUS = 0.0215
CAMERA_COUNT = 1
CAMERA_0_POSITION = 1 2 4
CAMERA_0_ORIENTATION_DEG = 0 0 0
CAMERA_0_FOCAL_LENGTH = 500
CAMERA_0_IMAGE_SIZE = 640 480
CAMERA_0_PHASE = 0
)";
}

VisionProfile parse(const std::string& text) {
  return load_vision_profile(ConfigFile::parse(text, "test.cfg"), "test");
}

// The error a profile text gives, or "" when it loads.
std::string error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const ConfigError& error) {
    return error.what();
  }
  return "";
}

}  // namespace

TEST(VisionProfile, MinimalProfileLoadsEveryValue) {
  const VisionProfile p = parse(minimal_profile());
  EXPECT_EQ(p.seed, 7u);
  EXPECT_DOUBLE_EQ(p.latency, 0.05);
  EXPECT_DOUBLE_EQ(p.robot_sigma_y, 0.02);
  EXPECT_DOUBLE_EQ(p.ball_sigma_y, 0.05);
  EXPECT_DOUBLE_EQ(p.ball_min_visible_fraction, 0.4);
  ASSERT_EQ(p.cameras.size(), 1u);
  const auto& c = p.cameras[0];
  EXPECT_DOUBLE_EQ(c.frame_rate, 60);
  EXPECT_DOUBLE_EQ(c.latency, 0.05);  // from the profile-wide value
  EXPECT_DOUBLE_EQ(c.processing_time, 0.01);
  EXPECT_DOUBLE_EQ(c.principal_x, 320);  // image centre by default
  EXPECT_DOUBLE_EQ(c.principal_y, 240);
  EXPECT_EQ(c.position_error, Eigen::Vector3d::Zero());
}

TEST(VisionProfile, CameraKeysOverrideProfileWideTiming) {
  const VisionProfile p = parse(minimal_profile() + R"(CAMERA_0_FRAME_RATE = 120
CAMERA_0_LATENCY = 0
CAMERA_0_LATENCY_JITTER = 0
CAMERA_0_PROCESSING_TIME = 0
CAMERA_0_PRINCIPAL_POINT = 300 200
CAMERA_0_CALIBRATION_ERROR_POSITION = 0.01 0.02 0.03
CAMERA_0_CALIBRATION_ERROR_ORIENTATION_DEG = 0 0 1
CAMERA_0_CALIBRATION_ERROR_FOCAL_LENGTH = -5
)");
  const auto& c = p.cameras[0];
  EXPECT_DOUBLE_EQ(c.frame_rate, 120);
  EXPECT_DOUBLE_EQ(c.latency, 0);
  EXPECT_DOUBLE_EQ(c.principal_x, 300);
  EXPECT_DOUBLE_EQ(c.position_error.z(), 0.03);
  EXPECT_NEAR(c.roll_pitch_yaw_error.z(), M_PI / 180, 1e-12);
  EXPECT_DOUBLE_EQ(c.focal_length_error, -5);
}

TEST(VisionProfile, ShippedCmdragons02IsThePapersSetup) {
  const VisionProfile p = load_vision_profile(kConfigDir, "cmdragons02");
  ASSERT_EQ(p.cameras.size(), 1u);
  EXPECT_DOUBLE_EQ(p.cameras[0].frame_rate, 30);
  // ~66 ms of the paper's ~100 ms belongs to vision (the radio adds the rest).
  EXPECT_NEAR(p.latency, 0.066, 0.01);
  EXPECT_GT(p.robot_sigma_x, 0);
  EXPECT_LT(p.robot_detection_probability, 1);
}

TEST(VisionProfile, ShippedModernHasFourUnsynchronisedCameras) {
  const VisionProfile p = load_vision_profile(kConfigDir, "modern");
  ASSERT_EQ(p.cameras.size(), 4u);
  bool phases_differ = false;
  bool some_calibration_error = false;
  for (const auto& c : p.cameras) {
    EXPECT_TRUE(c.frame_rate == 60 || c.frame_rate == 80) << c.frame_rate;
    EXPECT_GE(c.latency, 0.03);
    EXPECT_LE(c.latency, 0.04);
    phases_differ |= c.phase != p.cameras[0].phase;
    some_calibration_error |= c.position_error.norm() > 0 || c.roll_pitch_yaw_error.norm() > 0;
  }
  EXPECT_TRUE(phases_differ);
  EXPECT_TRUE(some_calibration_error);
}

TEST(VisionProfile, EveryShippedKeyStatesItsUnit) {
  // A key line must end in a comment ("# m", "# unitless ..."): the unit is documentation.
  const std::regex key_line(R"(^\s*([A-Z][A-Z0-9_]*)\s*=([^#]*)(#.*)?$)");
  for (const char* name : {"cmdragons02", "modern", "grsim", "grsim_div_b"}) {
    std::ifstream in(kConfigDir + "/vision/" + name + ".cfg");
    ASSERT_TRUE(in) << name;
    std::string line;
    int number = 0;
    while (std::getline(in, line)) {
      ++number;
      std::smatch match;
      if (!std::regex_match(line, match, key_line)) continue;
      EXPECT_TRUE(match[3].matched && match[3].length() > 2)
          << name << ".cfg:" << number << ": " << match[1] << " has no unit comment";
    }
  }
}

TEST(VisionProfile, UnknownKeyIsAnErrorNamingItsLine) {
  const std::string error = error_of(minimal_profile() + "FRAME_RATES = 30\n");
  EXPECT_NE(error.find("test.cfg:28"), std::string::npos) << error;
  EXPECT_NE(error.find("FRAME_RATES"), std::string::npos) << error;
}

TEST(VisionProfile, KeysOfCamerasBeyondTheCountAreUnknown) {
  const std::string error = error_of(minimal_profile() + "CAMERA_1_FOCAL_LENGTH = 500\n");
  EXPECT_NE(error.find("unknown key 'CAMERA_1_FOCAL_LENGTH'"), std::string::npos) << error;
}

TEST(VisionProfile, MissingCameraKeyIsNamed) {
  std::string text = minimal_profile();
  text.replace(text.find("CAMERA_0_FOCAL_LENGTH = 500\n"), 28, "");
  const std::string error = error_of(text);
  EXPECT_NE(error.find("CAMERA_0_FOCAL_LENGTH"), std::string::npos) << error;
}

TEST(VisionProfile, ImpossibleValuesAreErrorsAtTheirLine) {
  auto with = [](const std::string& key_line, const std::string& replacement) {
    std::string text = minimal_profile();
    text.replace(text.find(key_line), key_line.size(), replacement);
    return error_of(text);
  };
  // Processing cannot take longer than the whole latency.
  EXPECT_NE(with("PROCESSING_TIME = 0.01", "PROCESSING_TIME = 0.2").find("test.cfg:5"),
            std::string::npos);
  // A phase is within one frame period (1/60 s here).
  EXPECT_NE(with("CAMERA_0_PHASE = 0", "CAMERA_0_PHASE = 0.02").find("test.cfg:27"),
            std::string::npos);
  // A camera looking up at the sky sees no field.
  EXPECT_NE(with("CAMERA_0_ORIENTATION_DEG = 0 0 0", "CAMERA_0_ORIENTATION_DEG = 180 0 0")
                .find("look down"),
            std::string::npos);
  EXPECT_NE(with("BALL_DETECTION_PROBABILITY = 0.8", "BALL_DETECTION_PROBABILITY = 1.5")
                .find("test.cfg:13"),
            std::string::npos);
  EXPECT_NE(with("CAMERA_0_POSITION = 1 2 4", "CAMERA_0_POSITION = 1 2").find("3 values"),
            std::string::npos);
  EXPECT_NE(with("CAMERA_COUNT = 1", "CAMERA_COUNT = 0").find("CAMERA_COUNT"), std::string::npos);
  EXPECT_NE(with("SEED = 7", "SEED = -1").find("SEED"), std::string::npos);
}
