// The bridge's config: directions and topics per channel; every mistake is an
// error naming file and line.
#include <gtest/gtest.h>

#include "ubersim/config.hpp"
#include "ubersim/dds_bridge/bridge_config.hpp"
#include "ubersim/dds_bridge/qos.hpp"
#include "ubersim/topics.hpp"

namespace dds = ubersim::dds;
namespace topics = ubersim::topics;
using ubersim::ConfigError;
using ubersim::ConfigFile;

namespace {

dds::BridgeConfig parse(const std::string& text) {
  return dds::load_bridge_config(ConfigFile::parse(text, "test.cfg"), "test");
}

// The ConfigError message for `text`, or "" when it loads.
std::string error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const ConfigError& error) {
    return error.what();
  }
  return "";
}

}  // namespace

TEST(BridgeConfig, ShippedDefaultBridgesWhatADdsControlStackNeeds) {
  const auto config = dds::load_bridge_config(UBERSIM_SOURCE_CONFIG_DIR, "default");
  EXPECT_EQ(config.topic_prefix, "rt/ubersim/");
  EXPECT_EQ(config.radio_limits, "cmdragons02");
  const auto direction = [&](std::string_view channel) {
    const dds::Route* route = config.find(channel);
    return route == nullptr ? dds::Direction::Off : route->direction;
  };
  EXPECT_EQ(direction(topics::kVision.name), dds::Direction::LcmToDds);
  EXPECT_EQ(direction(topics::kSimState.name), dds::Direction::LcmToDds);
  EXPECT_EQ(direction(topics::kSimGeometry.name), dds::Direction::LcmToDds);
  EXPECT_EQ(direction(topics::kVisionGeometry.name), dds::Direction::LcmToDds);
  EXPECT_EQ(direction(topics::kRadio.yellow.name), dds::Direction::DdsToLcm);
  EXPECT_EQ(direction(topics::kRadio.blue.name), dds::Direction::DdsToLcm);
  EXPECT_EQ(direction(topics::kSimControl.name), dds::Direction::DdsToLcm);
  EXPECT_EQ(direction(topics::kSimCommands.name), dds::Direction::Off);
  EXPECT_EQ(config.find(topics::kVision)->topic, "rt/ubersim/vision");
  EXPECT_EQ(config.find(topics::kRadio.blue)->topic, "rt/ubersim/radio_blue");
}

TEST(BridgeConfig, TopicDefaultsToTheChannelNameAndCanBeNamed) {
  const auto config = parse(
      "TOPIC_PREFIX = rt/\n"
      "VISION = lcm_to_dds camera/detections\n"
      "SIM_STATE = both\n"
      "RADIO_BLUE = off\n");
  ASSERT_EQ(config.routes.size(), 2u);  // `off` is not a route
  EXPECT_EQ(config.find(topics::kVision)->topic, "rt/camera/detections");
  EXPECT_EQ(config.find(topics::kSimState)->topic, "rt/sim_state");
  EXPECT_EQ(config.find(topics::kSimState)->direction, dds::Direction::Both);
  EXPECT_EQ(config.find(topics::kRadio.blue), nullptr);
  EXPECT_EQ(config.radio_limits, "cmdragons02");  // the default
}

TEST(BridgeConfig, MistakesNameFileAndLine) {
  EXPECT_NE(error_of("VISION = lcm_to_dds\nSIM_STATE = sideways\n").find("test.cfg:2"),
            std::string::npos);
  EXPECT_NE(error_of("VISION = lcm_to_dds\nSIM_STATE = sideways\n").find("sideways"),
            std::string::npos);
  EXPECT_NE(error_of("VISON = lcm_to_dds\n").find("test.cfg:1"), std::string::npos);
  EXPECT_NE(error_of("VISON = lcm_to_dds\n").find("unknown key"), std::string::npos);
  EXPECT_NE(error_of("VISION = lcm_to_dds a b\n").find("at most one topic"), std::string::npos);
  EXPECT_NE(error_of("VISION = lcm_to_dds bad-name\n").find("bad-name"), std::string::npos);
  EXPECT_NE(error_of("TOPIC_PREFIX = rt.x\n").find("TOPIC_PREFIX"), std::string::npos);
  EXPECT_NE(error_of("VISION = lcm_to_dds same\nSIM_STATE = lcm_to_dds same\n").find("test.cfg:2"),
            std::string::npos);
}

TEST(BridgeConfig, QosFollowsTheUseOfEachChannel) {
  EXPECT_EQ(dds::topic_use(topics::kVision), dds::TopicUse::Stream);
  EXPECT_EQ(dds::topic_use(topics::kSimState), dds::TopicUse::Stream);
  EXPECT_EQ(dds::topic_use(topics::kSimGeometry), dds::TopicUse::Geometry);
  EXPECT_EQ(dds::topic_use(topics::kVisionGeometry), dds::TopicUse::Geometry);
  EXPECT_EQ(dds::topic_use(topics::kRadio.yellow), dds::TopicUse::Command);
  EXPECT_EQ(dds::topic_use(topics::kSimControl), dds::TopicUse::Command);
  const auto stream = dds::qos_settings(dds::TopicUse::Stream);
  EXPECT_FALSE(stream.reliable);
  EXPECT_EQ(stream.writer_depth, 1);
  const auto geometry = dds::qos_settings(dds::TopicUse::Geometry);
  EXPECT_TRUE(geometry.reliable);
  EXPECT_TRUE(geometry.transient_local);
  EXPECT_EQ(geometry.writer_depth, 1);
  const auto command = dds::qos_settings(dds::TopicUse::Command);
  EXPECT_TRUE(command.reliable);
  EXPECT_FALSE(command.transient_local);
}
