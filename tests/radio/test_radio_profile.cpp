// Emulator profiles: the shipped ones load and say what the issue asks; a
// broken profile is an error that names file, line and what was expected.
#include <gtest/gtest.h>

#include "radio_test_util.hpp"
#include "ubersim/radio/radio_profile.hpp"

using ubersim::ConfigError;
using ubersim::ConfigFile;
using ubersim::radio::load_radio_profile;

TEST(RadioProfile, Cmdragons02IsThePapersLink) {
  const auto p = load_radio_profile(UBERSIM_SOURCE_CONFIG_DIR, "cmdragons02");
  EXPECT_EQ(p.max_packet_rate, 60);
  // With the vision emulator's 66 ms, the paper's ~100 ms from camera to robot.
  EXPECT_NEAR(0.066 + p.command.latency, 0.1, 0.002);
  EXPECT_GT(p.command.packet_loss, 0);
  EXPECT_LT(p.command.packet_loss, 0.05);
  EXPECT_GE(p.command_timeout, 0.2);
  EXPECT_LE(p.command_timeout, 0.5);
  EXPECT_GT(p.feedback_rate, 0);
}

TEST(RadioProfile, ModernIsFasterAndQuicker) {
  const auto p = load_radio_profile(UBERSIM_SOURCE_CONFIG_DIR, "modern");
  EXPECT_GE(p.max_packet_rate, 100);
  EXPECT_GE(p.command.latency, 0.010);
  EXPECT_LE(p.command.latency, 0.015);
  EXPECT_GT(p.command.packet_loss, 0);
  EXPECT_LT(p.command.packet_loss, 0.05);
}

TEST(RadioProfile, IdealHasNoLimitDelayOrLoss) {
  const auto p = load_radio_profile(UBERSIM_SOURCE_CONFIG_DIR, "ideal");
  EXPECT_EQ(p.max_packet_rate, 0);
  EXPECT_EQ(p.command.latency, 0);
  EXPECT_EQ(p.command.packet_loss + p.command.robot_loss, 0);
  EXPECT_EQ(p.feedback.packet_loss + p.feedback.robot_loss, 0);
}

// The radio half of `--profile grsim`: grSim applies commands at once and
// stops robots after 1 s without a command.
TEST(RadioProfile, GrsimHasNoDelayOrLossAndStopsAfterOneSecond) {
  const auto p = load_radio_profile(UBERSIM_SOURCE_CONFIG_DIR, "grsim");
  EXPECT_EQ(p.command.latency, 0);
  EXPECT_EQ(p.command.packet_loss + p.command.robot_loss, 0);
  EXPECT_EQ(p.command_timeout, 1.0);
}

TEST(RadioProfile, EveryKeyIsRead) {
  const auto p = radio_test::profile(50, 0.02, 0.001, 0.1, 0.05);
  EXPECT_EQ(p.max_packet_rate, 50);
  EXPECT_EQ(p.command.latency, 0.02);
  EXPECT_EQ(p.command.latency_jitter, 0.001);
  EXPECT_EQ(p.command.packet_loss, 0.1);
  EXPECT_EQ(p.command.robot_loss, 0.05);
  EXPECT_EQ(p.command_timeout, 0.25);
  EXPECT_EQ(p.feedback_rate, 30);
  EXPECT_EQ(p.feedback.latency, 0.02);
  EXPECT_EQ(p.limits.speed, 10);
  EXPECT_EQ(p.limits.angular_speed, 60);
  EXPECT_EQ(p.limits.wheel_speed, 1000);
  EXPECT_EQ(p.limits.kick_speed, 20);
  EXPECT_EQ(p.limits.dribbler_speed, 5000);
  EXPECT_EQ(p.seed, 7u);
}

namespace {
std::string error_of(const std::string& text) {
  try {
    load_radio_profile(ConfigFile::parse(text, "bad.cfg"), "bad");
  } catch (const ConfigError& error) {
    return error.what();
  }
  return "no error";
}
}  // namespace

TEST(RadioProfile, UnknownKeyIsAnErrorAtItsLine) {
  const std::string text = radio_test::profile_text(60, 0.03, 0, 0, 0) + "LATENCY_MS = 33\n";
  const std::string error = error_of(text);
  EXPECT_NE(error.find("bad.cfg:"), std::string::npos) << error;
  EXPECT_NE(error.find("LATENCY_MS"), std::string::npos) << error;
}

TEST(RadioProfile, OutOfRangeValuesAreErrors) {
  EXPECT_NE(error_of(radio_test::profile_text(60, 0.03, 0, 1.5, 0)).find("PACKET_LOSS"),
            std::string::npos);
  EXPECT_NE(error_of(radio_test::profile_text(-1, 0.03, 0, 0, 0)).find("MAX_PACKET_RATE"),
            std::string::npos);
  EXPECT_NE(error_of(radio_test::profile_text(60, -0.03, 0, 0, 0)).find("LATENCY"),
            std::string::npos);
}

TEST(RadioProfile, MissingKeyIsAnError) {
  std::string text = radio_test::profile_text(60, 0.03, 0, 0, 0);
  text.erase(text.find("SEED"));
  EXPECT_NE(error_of(text).find("SEED"), std::string::npos);
}

TEST(RadioProfile, UnknownProfileNameListsTheAvailableOnes) {
  try {
    load_radio_profile(UBERSIM_SOURCE_CONFIG_DIR, "no_such_radio");
    FAIL();
  } catch (const ConfigError& error) {
    EXPECT_NE(std::string(error.what()).find("cmdragons02"), std::string::npos) << error.what();
  }
}
