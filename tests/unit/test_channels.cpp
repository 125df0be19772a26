#include <gtest/gtest.h>

#include <set>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "ubersim/channels.hpp"
#include "ubersim/common_options.hpp"
#include "ubersim/field_side.hpp"
#include "ubersim/topics.hpp"

using ubersim::channel_name;
using ubersim::ChannelNames;
using ubersim::Team;
namespace topics = ubersim::topics;

TEST(Channels, DefaultNamesMatchTheRealServers) {
  const ChannelNames names;
  EXPECT_EQ(channel_name(names, topics::kVision), "VISION");
  EXPECT_EQ(channel_name(names, topics::kRadio.of(Team::Yellow)), "RADIO_YELLOW");
  EXPECT_EQ(channel_name(names, topics::kRadio.of(Team::Blue)), "RADIO_BLUE");
  EXPECT_EQ(channel_name(names, topics::kRadioFeedback.of(Team::Blue)), "RADIO_FEEDBACK_BLUE");
  EXPECT_EQ(channel_name(names, topics::kSimState), "SIM_STATE");
}

TEST(Channels, EveryChannelHasADistinctName) {
  const ChannelNames names;
  std::set<std::string> seen;
  for (std::string_view base : topics::kAllNames) {
    EXPECT_TRUE(seen.insert(names.resolve(base)).second) << base;
  }
}

TEST(Channels, PrefixAppliesToEveryChannel) {
  const ChannelNames names("SIM2_", {});
  for (std::string_view base : topics::kAllNames) {
    EXPECT_EQ(names.resolve(base), "SIM2_" + std::string(base));
  }
}

TEST(Channels, EveryChannelCanBeOverridden) {
  for (std::string_view base : topics::kAllNames) {
    const ChannelNames names("P_", {{std::string(base), "MINE"}});
    EXPECT_EQ(names.resolve(base), "MINE");
  }
}

TEST(Channels, OverrideBeatsPrefix) {
  const ChannelNames names("P_", {{"VISION", "CAMERAS"}});
  EXPECT_EQ(channel_name(names, topics::kVision), "CAMERAS");
  EXPECT_EQ(channel_name(names, topics::kSimState), "P_SIM_STATE");
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

namespace typed_topics {
using ubersim::ChannelNames;
using ubersim::MessageBus;
using ubersim::Topic;

// Whether publish(bus, channels, Topic<T>, M) compiles.
template <class T, class M, class = void>
struct can_publish : std::false_type {};
template <class T, class M>
struct can_publish<T, M,
                   std::void_t<decltype(ubersim::publish(
                       std::declval<MessageBus&>(), std::declval<const ChannelNames&>(),
                       std::declval<const Topic<T>&>(), std::declval<const M&>()))>>
    : std::true_type {};

// A topic's own message publishes; any other type does not compile.
static_assert(can_publish<ubersim::sim_state_t, ubersim::sim_state_t>::value);
static_assert(!can_publish<ubersim::sim_state_t, ubersim::referee_t>::value);
static_assert(!can_publish<ubersim::radio_packet_t, ubersim::radio_feedback_t>::value);

// A Publisher takes its topic's message only.
static_assert(std::is_invocable_v<ubersim::Publisher<ubersim::sim_state_t>, ubersim::sim_state_t>);
static_assert(!std::is_invocable_v<ubersim::Publisher<ubersim::sim_state_t>, ubersim::referee_t>);
}  // namespace typed_topics

// Every topic has its row in the README's table (printed from the topics).
TEST(Channels, EveryTopicHasARowInTheTable) {
  std::set<std::string> in_table;
  for (const auto& row : ubersim::topic_table()) in_table.insert(row.channels);
  std::string all;
  for (const auto& name : in_table) all += name + " ";
  for (std::string_view base : topics::kAllNames) {
    const std::string quoted = "`" + std::string(base) + "`";
    EXPECT_NE(all.find(quoted), std::string::npos) << quoted << " has no row";
  }
  const ChannelNames channels("P_", {{"SIM_STATE", "TRUTH"}});
  EXPECT_EQ(ubersim::channel_name(channels, ubersim::topics::kSimState), "TRUTH");
  EXPECT_EQ(ubersim::channel_name(channels, ubersim::topics::kReferee), "P_REFEREE");
  EXPECT_EQ(ubersim::channel_name(channels, ubersim::topics::kRadio.of(ubersim::Team::Blue)),
            "P_RADIO_BLUE");
}

// A Publisher sends on the channel name the process gives its topic (prefix
// and overrides applied once, when it is made), over the real bus.
TEST(Channels, PublisherSendsOnTheTopicsChannelInThisProcess) {
  ubersim::MessageBus bus("memq://");
  const ChannelNames channels("P_", {{"RADIO_FEEDBACK_BLUE", "FB"}});
  const ubersim::Publisher<ubersim::radio_feedback_t> feedback(
      bus, channels, ubersim::topics::kRadioFeedback.of(Team::Blue));
  const ubersim::Publisher<ubersim::sim_commands_t> commands(bus, channels,
                                                             ubersim::topics::kSimCommands);
  EXPECT_EQ(feedback.channel(), "FB");
  EXPECT_EQ(commands.channel(), "P_SIM_COMMANDS");
  std::vector<std::string> heard;
  bus.subscribe<ubersim::radio_feedback_t>(
      "FB", [&](const ubersim::radio_feedback_t&) { heard.push_back("feedback"); });
  bus.subscribe<ubersim::sim_commands_t>(
      "P_SIM_COMMANDS", [&](const ubersim::sim_commands_t&) { heard.push_back("commands"); });
  commands(ubersim::sim_commands_t{});
  feedback(ubersim::radio_feedback_t{});
  bus.handle_pending();
  EXPECT_EQ(heard, (std::vector<std::string>{"commands", "feedback"}));
}

// The side a team defends: one parser for every program and the Python module.
TEST(DefendedSide, NegativeAndPositiveOnly) {
  EXPECT_EQ(ubersim::parse_defended_side("negative"), -1);
  EXPECT_EQ(ubersim::parse_defended_side("positive"), 1);
  EXPECT_THROW(ubersim::parse_defended_side("Positive"), std::invalid_argument);
  EXPECT_THROW(ubersim::parse_defended_side("-1"), std::invalid_argument);
  EXPECT_THROW(ubersim::parse_defended_side(""), std::invalid_argument);
}
