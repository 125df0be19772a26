#include <gtest/gtest.h>

#include <set>

#include "ubersim/channels.hpp"
#include "ubersim/cli.hpp"

using ubersim::Channel;
using ubersim::ChannelNames;
using ubersim::Team;

TEST(Channels, DefaultNamesMatchTheRealServers) {
  const ChannelNames names;
  EXPECT_EQ(names(Channel::Vision), "VISION");
  EXPECT_EQ(names.radio(Team::Yellow), "RADIO_YELLOW");
  EXPECT_EQ(names.radio(Team::Blue), "RADIO_BLUE");
  EXPECT_EQ(names.radio_feedback(Team::Blue), "RADIO_FEEDBACK_BLUE");
  EXPECT_EQ(names(Channel::SimState), "SIM_STATE");
}

TEST(Channels, EveryChannelHasADistinctName) {
  const ChannelNames names;
  std::set<std::string> seen;
  for (Channel channel : ubersim::kAllChannels) EXPECT_TRUE(seen.insert(names(channel)).second);
}

TEST(Channels, PrefixAppliesToEveryChannel) {
  const ChannelNames names("SIM2_", {});
  for (Channel channel : ubersim::kAllChannels) {
    EXPECT_EQ(names(channel), std::string("SIM2_") + ubersim::base_channel_name(channel));
  }
}

TEST(Channels, OverrideBeatsPrefix) {
  const ChannelNames names("P_", {{"VISION", "CAMERAS"}});
  EXPECT_EQ(names(Channel::Vision), "CAMERAS");
  EXPECT_EQ(names(Channel::SimState), "P_SIM_STATE");
}

TEST(Channels, BadOverridesAreRejected) {
  EXPECT_THROW(ChannelNames("", {{"VISON", "X"}}), std::invalid_argument);
  EXPECT_THROW(ChannelNames::parse_override("VISION"), std::invalid_argument);
  EXPECT_THROW(ChannelNames::parse_override("VISION="), std::invalid_argument);
  EXPECT_EQ(ChannelNames::parse_override("VISION=A=B").second, "A=B");
}

TEST(Channels, TeamsParse) {
  Team team{};
  EXPECT_TRUE(ubersim::parse_team("blue", team));
  EXPECT_EQ(team, Team::Blue);
  EXPECT_TRUE(ubersim::parse_team("y", team));
  EXPECT_EQ(team, Team::Yellow);
  EXPECT_FALSE(ubersim::parse_team("green", team));
}

TEST(Channels, ReceiveBufferIsAddedOnlyToMulticastUrls) {
  EXPECT_EQ(ubersim::with_receive_buffer("udpm://239.255.76.67:7667?ttl=0"),
            "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304");
  EXPECT_EQ(ubersim::with_receive_buffer("udpm://239.255.76.67:7667"),
            "udpm://239.255.76.67:7667?recv_buf_size=4194304");
  EXPECT_EQ(ubersim::with_receive_buffer("memq://"), "memq://");
  EXPECT_EQ(ubersim::with_receive_buffer("udpm://1.2.3.4:5?recv_buf_size=9"),
            "udpm://1.2.3.4:5?recv_buf_size=9");
}
