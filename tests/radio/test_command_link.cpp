// The command link model in-process: rate limit (latest wins), latency in sim
// time, order, loss statistics, seeding.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <optional>

#include "radio_test_util.hpp"
#include "ubersim/radio/command_link.hpp"

using radio_test::packet;
using radio_test::profile;
using ubersim::Team;
using ubersim::radio::CommandLink;

namespace {
constexpr double kStep = 1.0 / 240;  // physics step of the paper-style setup (s)
constexpr double kTight = 1e-9;      // s, float round-off only
}  // namespace

TEST(CommandLink, FreeLinkForwardsAtOnceWithTheLatencyInSimTime) {
  CommandLink link(profile(60, 0.033), Team::Yellow, 1);
  const auto out = link.offer(packet(0, 5, {1, 2}), 2.0);
  ASSERT_TRUE(out.has_value());
  EXPECT_EQ(out->team, 0);
  EXPECT_EQ(out->sequence, 5);
  EXPECT_DOUBLE_EQ(out->t_received, 2.0);
  EXPECT_NEAR(out->t_apply, 2.033, kTight);
  EXPECT_DOUBLE_EQ(out->command_timeout, 0.25);
  EXPECT_EQ(out->num_commands, 2);
}

TEST(CommandLink, BusyLinkKeepsOnlyTheNewestPacketAndSendsItWhenFree) {
  CommandLink link(profile(60, 0.033), Team::Yellow, 1);
  ASSERT_TRUE(link.offer(packet(0, 1, {0}), 0.0));     // link busy until 1/60 s
  EXPECT_FALSE(link.offer(packet(0, 2, {0}), 0.005));  // waits
  EXPECT_FALSE(link.offer(packet(0, 3, {0}), 0.010));  // replaces 2
  EXPECT_FALSE(link.poll(0.015));                      // still busy
  const auto out = link.poll(0.02);                    // the step after the link freed
  ASSERT_TRUE(out.has_value());
  EXPECT_EQ(out->sequence, 3);
  EXPECT_DOUBLE_EQ(out->t_received, 0.010);
  // Transmitted the moment the link freed (1/60 s), not when the step noticed.
  EXPECT_NEAR(out->t_apply, 1.0 / 60 + 0.033, kTight);
  EXPECT_EQ(link.stats().superseded, 1u);
  EXPECT_EQ(link.stats().transmitted, 2u);
  EXPECT_FALSE(link.poll(1.0));  // nothing left
}

// A 200 Hz sender against a 60 Hz link, polled at 240 Hz: every forwarded
// packet is the newest offered before its transmission, and the rate is exact.
TEST(CommandLink, SaturatedLinkRunsAtItsRateAndForwardsTheNewest) {
  const double latency = 0.033;
  CommandLink link(profile(60, latency), Team::Yellow, 1);
  std::vector<std::pair<double, std::int64_t>> forwarded;  // (t_transmit, sequence)
  std::int64_t newest = -1;
  std::int64_t next_packet = 0;
  const auto take = [&](const std::optional<ubersim::sim_commands_t>& out, std::int64_t expected) {
    if (!out) return;
    EXPECT_EQ(out->sequence, expected);
    forwarded.emplace_back(out->t_apply - latency, out->sequence);
  };
  const int steps = 240 * 100;
  for (int k = 0; k < steps; ++k) {
    const double now = k * kStep;
    take(link.poll(now), newest);
    while (next_packet / 200.0 <= now + kTight) {
      newest = next_packet++;
      take(link.offer(packet(0, newest, {0}), now), newest);
    }
  }
  // 100 s at 60 Hz: 6000 transmissions (at n / 60 s, n = 0 .. 5999).
  EXPECT_EQ(forwarded.size(), 6000u);
  for (std::size_t i = 1; i < forwarded.size(); ++i)
    ASSERT_NEAR(forwarded[i].first - forwarded[i - 1].first, 1.0 / 60, 1e-9) << i;
}

// The point of stamping transmissions when the link frees: a rate that is not
// a whole fraction of the physics rate still comes out exact on average.
TEST(CommandLink, RateHoldsWhenItDoesNotDivideThePhysicsRate) {
  CommandLink link(profile(100, 0.01), Team::Blue, 1);
  int forwarded = 0;
  std::int64_t sequence = 0;
  for (int k = 0; k < 240 * 60; ++k) {  // 60 s of sim time
    const double now = k * kStep;
    if (link.poll(now)) ++forwarded;
    if (link.offer(packet(1, sequence++, {0}), now)) ++forwarded;  // sender at 240 Hz
  }
  EXPECT_NEAR(forwarded / 60.0, 100.0, 100.0 * 0.002);
}

TEST(CommandLink, UnlimitedRateForwardsEveryPacket) {
  CommandLink link(profile(0, 0), Team::Yellow, 1);
  for (int i = 0; i < 50; ++i) ASSERT_TRUE(link.offer(packet(0, i, {0}), 1.0));
}

TEST(CommandLink, JitterNeverReordersNorSendsIntoThePast) {
  // Jitter as large as the packet spacing: many draws would overtake.
  const double latency = 0.02;
  CommandLink link(profile(0, latency, 0.03), Team::Yellow, 3);
  double previous = -1;
  int delayed_by_order = 0;
  for (int i = 0; i < 5000; ++i) {
    const double now = i * 0.01;
    const auto out = link.offer(packet(0, i, {0}), now);
    ASSERT_TRUE(out.has_value());
    ASSERT_GE(out->t_apply, now);
    ASSERT_GE(out->t_apply, previous);
    if (out->t_apply == previous) ++delayed_by_order;
    previous = out->t_apply;
  }
  EXPECT_GT(delayed_by_order, 0);  // the order clamp did act
}

TEST(CommandLink, JitterHasTheConfiguredMeanAndSigma) {
  const double latency = 0.033, sigma = 0.002;
  CommandLink link(profile(60, latency, sigma), Team::Yellow, 11);
  const int n = 20000;
  double sum = 0, sum_sq = 0;
  for (int i = 0; i < n; ++i) {
    const double now = i * (1.0 / 30);  // below the rate limit: never waits
    const auto out = link.offer(packet(0, i, {0}), now);
    ASSERT_TRUE(out.has_value());
    const double delay = out->t_apply - now;
    sum += delay;
    sum_sq += delay * delay;
  }
  const double mean = sum / n;
  const double sd = std::sqrt(sum_sq / n - mean * mean);
  EXPECT_NEAR(mean, latency, 3 * sigma / std::sqrt(n));
  EXPECT_NEAR(sd, sigma, 3 * sigma / std::sqrt(2.0 * n));
}

TEST(CommandLink, LossRatesMatchTheProfileWithinThreeStandardErrors) {
  const double p = 0.2, q = 0.1;
  CommandLink link(profile(0, 0.01, 0, p, q), Team::Blue, 5);
  const int n = 100000, robots = 6;
  int forwarded = 0;
  long entries = 0;
  for (int i = 0; i < n; ++i) {
    if (const auto out = link.offer(packet(1, i, {0, 1, 2, 3, 4, 5}), i * 0.01)) {
      ++forwarded;
      entries += out->num_commands;
    }
  }
  const auto& stats = link.stats();
  EXPECT_EQ(stats.transmitted, static_cast<std::uint64_t>(n));
  const double packet_loss = static_cast<double>(stats.lost_packets) / n;
  EXPECT_NEAR(packet_loss, p, 3 * std::sqrt(p * (1 - p) / n));
  const double through = static_cast<double>(n - stats.lost_packets) * robots;
  const double robot_loss = stats.lost_entries / through;
  EXPECT_NEAR(robot_loss, q, 3 * std::sqrt(q * (1 - q) / through));
  EXPECT_EQ(static_cast<double>(entries), through - stats.lost_entries);
  EXPECT_EQ(stats.forwarded_packets, static_cast<std::uint64_t>(forwarded));
}

TEST(CommandLink, LostPacketsStillUseTheirTransmissionSlot) {
  CommandLink link(profile(10, 0, 0, 1.0, 0), Team::Yellow, 1);  // everything lost
  for (int k = 0; k < 1000; ++k) {
    const double now = k * 0.01;  // 10 s
    link.poll(now);
    link.offer(packet(0, k, {0}), now);
  }
  EXPECT_EQ(link.stats().transmitted, 100u);
  EXPECT_EQ(link.stats().lost_packets, 100u);
  EXPECT_EQ(link.stats().forwarded_packets, 0u);
}

TEST(CommandLink, SameSeedSameDrawsOtherSeedOrTeamOtherDraws) {
  const auto run = [](std::uint64_t seed, Team team) {
    CommandLink link(profile(0, 0.03, 0.005, 0.3, 0.2), team, seed);
    std::vector<double> trace;
    for (int i = 0; i < 500; ++i) {
      const auto out = link.offer(packet(static_cast<int>(team), i, {0, 1, 2}), i * 0.02);
      trace.push_back(out ? out->t_apply + 1000.0 * out->num_commands : -1.0);
    }
    return trace;
  };
  EXPECT_EQ(run(42, Team::Yellow), run(42, Team::Yellow));
  EXPECT_NE(run(42, Team::Yellow), run(43, Team::Yellow));
  EXPECT_NE(run(42, Team::Yellow), run(42, Team::Blue));
}

TEST(CommandLink, ResetForgetsTheWaitingPacketAndTheBusyLink) {
  CommandLink link(profile(1, 0.1), Team::Yellow, 1);
  ASSERT_TRUE(link.offer(packet(0, 1, {0}), 50.0));  // busy until 51 s
  EXPECT_FALSE(link.offer(packet(0, 2, {0}), 50.5));
  link.reset();
  EXPECT_FALSE(link.has_waiting_packet());
  const auto out = link.offer(packet(0, 3, {0}), 0.0);  // sim time restarted
  ASSERT_TRUE(out.has_value());
  EXPECT_NEAR(out->t_apply, 0.1, kTight);
}
