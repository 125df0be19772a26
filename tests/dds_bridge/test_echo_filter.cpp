// The LCM side's loop guard: what the bridge published is recognised when it
// comes back, for a while, and nothing else is.
#include <gtest/gtest.h>

#include "sample_messages.hpp"
#include "ubersim/dds_bridge/echo_filter.hpp"

using ubersim::dds::EchoFilter;
using ubersim::dds::lcm_bytes;

TEST(EchoFilter, RecognisesWhatWasPublishedAndNothingElse) {
  EchoFilter filter;
  EXPECT_TRUE(filter.empty());
  const auto sent = lcm_bytes(dds_test::radio_packet(0, 1));
  filter.remember(sent);
  EXPECT_FALSE(filter.empty());
  EXPECT_TRUE(filter.is_echo(sent));
  EXPECT_TRUE(filter.is_echo(lcm_bytes(dds_test::radio_packet(0, 1))));  // same values
  EXPECT_FALSE(filter.is_echo(lcm_bytes(dds_test::radio_packet(0, 2))));
}

TEST(EchoFilter, ForgetsAfterTheWindow) {
  const auto t0 = EchoFilter::Clock::time_point{} + std::chrono::hours(1);
  EchoFilter filter(std::chrono::seconds(2));
  const auto sent = lcm_bytes(dds_test::vision_frame(5));
  filter.remember(sent, t0);
  EXPECT_TRUE(filter.is_echo(sent, t0 + std::chrono::milliseconds(1999)));
  EXPECT_FALSE(filter.is_echo(sent, t0 + std::chrono::milliseconds(2001)));
  EXPECT_TRUE(filter.empty());
}

TEST(EchoFilter, KeepsAtMostItsCapacity) {
  EchoFilter filter(std::chrono::seconds(2), 3);
  const auto now = EchoFilter::Clock::now();
  for (int i = 0; i < 4; ++i) filter.remember(lcm_bytes(dds_test::radio_packet(0, i)), now);
  EXPECT_FALSE(filter.is_echo(lcm_bytes(dds_test::radio_packet(0, 0)), now));  // oldest went
  EXPECT_TRUE(filter.is_echo(lcm_bytes(dds_test::radio_packet(0, 3)), now));
}
