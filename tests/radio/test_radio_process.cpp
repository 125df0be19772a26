// The real ubersim_radio process over real LCM (run ISOLATED): rate limit,
// latency, loss, feedback, bad input. Everything runs in sim time driven by
// the test, so the outcome does not depend on how busy the machine is.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

#include "radio_process_fixture.hpp"
#include "ubersim/topics.hpp"

using radio_test::packet;
using radio_test::profile_text;
using radio_test::RadioDriver;
using radio_test::RadioProcessTest;

namespace {
constexpr double kStep = RadioDriver::kStep;
constexpr double kEps = 1e-9;
constexpr int kSyncEvery = 12;  // steps between catch-ups (50 ms of sim time)
}  // namespace

// Issue test 1: a 60 Hz link and a 200 Hz sender.
TEST_F(RadioProcessTest, RateLimitForwardsTheNewestPacketAtTheConfiguredRate) {
  const double latency = 0.033;
  start(profile_text(60, latency, 0, 0, 0), 2);
  std::map<std::int64_t, double> stamp;  // sequence -> sim time it arrived at
  std::vector<double> state_times;
  std::int64_t next = 0;
  const int steps = 240 * 12;
  for (int k = 1; k <= steps; ++k) {
    driver_->publish_state(k);
    state_times.push_back(k * kStep);
    while (next / 200.0 <= k * kStep + kEps) {  // the 200 Hz sender, in sim time
      driver_->send(0, packet(0, next, {0, 1}));
      stamp[next] = k * kStep;
      ++next;
    }
    if (k % kSyncEvery == 0) {
      ASSERT_TRUE(driver_->sync());
    }
  }
  const auto& forwarded = driver_->commands(0);
  ASSERT_GT(forwarded.size(), 100u);

  int in_window = 0;  // transmissions in [1 s, 11 s)
  for (const auto& m : forwarded) {
    const double t_transmit = m.t_apply - latency;
    if (t_transmit >= 1 - kEps && t_transmit < 11 - kEps) ++in_window;
    ASSERT_TRUE(stamp.count(m.sequence));
    EXPECT_NEAR(m.t_received, stamp[m.sequence], kEps);
    ASSERT_EQ(m.num_commands, 2);
    EXPECT_NEAR(m.commands[0].vx, 1e-4 * m.sequence, 1e-12);  // forwarded unchanged
    // The transmission happened while the emulator handled the first SIM_STATE
    // at or after t_transmit; what it had then was every packet sent before
    // that state. The newest of those must be the one that went out -- unless
    // the link was idle and this packet went out the moment it arrived.
    const double handled_at =
        *std::lower_bound(state_times.begin(), state_times.end(), t_transmit - kEps);
    std::int64_t newest = -1;
    for (const auto& [sequence, t] : stamp)
      if (t < handled_at - kEps) newest = std::max(newest, sequence);
    if (std::abs(m.t_received - t_transmit) < kEps) continue;  // sent on arrival
    EXPECT_EQ(m.sequence, newest) << "transmitted at " << t_transmit;
  }
  const double rate = in_window / 10.0;
  EXPECT_NEAR(rate, 60, 60 * 0.02);
  std::cout << "forwarded rate " << rate << " Hz from a 200 Hz sender through a 60 Hz link\n";
}

// Issue test 2: forwarded minus received equals the latency; order is kept.
TEST_F(RadioProcessTest, LatencyIsAppliedInSimTimeAndOrderIsKept) {
  const double latency = 0.033;
  start(profile_text(60, latency, 0, 0, 0), 2);
  std::map<std::int64_t, double> stamp;
  std::int64_t sequence = 0;
  for (int k = 1; k <= 240 * 10; ++k) {
    driver_->publish_state(k);
    if (k % 6 == 0) {  // 40 Hz: the 60 Hz link is always free
      driver_->send(0, packet(0, sequence, {0}));
      stamp[sequence++] = k * kStep;
    }
    if (k % kSyncEvery == 0) {
      ASSERT_TRUE(driver_->sync());
    }
  }
  const auto& forwarded = driver_->commands(0);
  ASSERT_EQ(forwarded.size(), stamp.size());  // nothing lost, nothing held back
  double worst = 0;
  for (std::size_t i = 0; i < forwarded.size(); ++i) {
    const auto& m = forwarded[i];
    EXPECT_EQ(m.sequence, static_cast<std::int64_t>(i));  // in order
    EXPECT_NEAR(m.t_received, stamp[m.sequence], kEps);   // the latest SIM_STATE's time
    const double delay = m.t_apply - m.t_received;
    worst = std::max(worst, std::abs(delay - latency));
    EXPECT_GE(delay, latency - kEps);
    EXPECT_LT(delay, latency + kStep);
    if (i > 0) {
      EXPECT_GE(m.t_apply, forwarded[i - 1].t_apply);
    }
  }
  std::cout << "worst |t_apply - t_received - latency| = " << worst << " s over "
            << forwarded.size() << " packets\n";
}

// Issue test 3: loss rates within 3 standard errors, through the real process.
TEST_F(RadioProcessTest, LossRatesMatchTheProfileWithinThreeStandardErrors) {
  const double p = 0.2, q = 0.1;
  const int robots = 6;
  start(profile_text(60, 0.02, 0, p, q), robots);
  const int n = 1200;
  for (int k = 1, sent = 0; sent < n; ++k) {
    driver_->publish_state(k);
    if (k % 5 == 0) {  // 48 Hz: below the link's rate, every packet is transmitted
      driver_->send(0, packet(0, sent++, {0, 1, 2, 3, 4, 5}));
    }
    if (k % kSyncEvery == 0) {
      ASSERT_TRUE(driver_->sync());
    }
  }
  for (int k = 0; k < 24; ++k) driver_->publish_state(240 * 30 + k);  // let the last ones out
  ASSERT_TRUE(driver_->sync());
  const auto& forwarded = driver_->commands(0);
  long entries = 0;
  for (const auto& m : forwarded) entries += m.num_commands;
  // A packet is missing when lost whole or (negligibly, q^6 = 1e-6) when every entry was lost.
  const double packet_loss = 1.0 - static_cast<double>(forwarded.size()) / n;
  const double se_packet = std::sqrt(p * (1 - p) / n);
  EXPECT_NEAR(packet_loss, p, 3 * se_packet);
  const double delivered_entries = static_cast<double>(forwarded.size()) * robots;
  const double robot_loss = 1.0 - entries / delivered_entries;
  const double se_robot = std::sqrt(q * (1 - q) / delivered_entries);
  EXPECT_NEAR(robot_loss, q, 3 * se_robot);
  std::cout << "packet loss " << packet_loss << " (configured " << p << ", 3 SE " << 3 * se_packet
            << "); robot loss " << robot_loss << " (configured " << q << ", 3 SE " << 3 * se_robot
            << ")\n";
}

// Issue test 5: feedback reaches the team with the configured latency.
TEST_F(RadioProcessTest, FeedbackReachesTheTeamWithTheConfiguredLatency) {
  const double feedback_latency = 0.02;  // profile_text: 30 Hz, 20 ms, no loss
  const auto contact = [](std::int64_t step, int id) { return (step / 5 + id) % 2 == 0; };
  const auto charged = [](std::int64_t step, int id) { return (step / 11 + id) % 3 != 0; };
  start(profile_text(60, 0.033, 0, 0, 0), 3, [&](ubersim::sim_state_t& s) {
    for (auto& r : s.robots) {
      r.ball_contact = contact(s.step, r.robot_id);
      r.kicker_charged = charged(s.step, r.robot_id);
    }
  });
  const int steps = 240 * 10;
  for (int k = 1; k <= steps; ++k) {
    driver_->publish_state(k);
    if (k % kSyncEvery == 0) {
      ASSERT_TRUE(driver_->sync());
    }
  }
  for (int team = 0; team < 2; ++team) {
    const auto& feedback = driver_->feedback(team);
    // 30 Hz for 10 s (the blue profile has the same feedback settings).
    EXPECT_NEAR(static_cast<double>(feedback.size()), 300, 2) << "team " << team;
    const double latency = feedback_latency;
    for (const auto& received : feedback) {
      const auto& fb = received.message;
      EXPECT_EQ(fb.team, team);
      const double delay = fb.t_sent - fb.t_measured;
      EXPECT_GE(delay, latency - kEps);
      EXPECT_LT(delay, latency + kStep);
      // Published when sim time got there, not before.
      EXPECT_LE(fb.t_sent, received.last_state_published + kEps);
      const std::int64_t step = std::llround(fb.t_measured / kStep);
      ASSERT_EQ(fb.num_robots, 3);
      for (const auto& r : fb.robots) {
        EXPECT_EQ(r.ball_contact, contact(step, r.robot_id)) << step;
        EXPECT_EQ(r.kicker_charged, charged(step, r.robot_id)) << step;
      }
    }
  }
}

// Issue item 6: bad input is counted, logged at most once per second per kind,
// never forwarded as is; malformed LCM does not crash the process.
TEST_F(RadioProcessTest, BadInputIsCountedNeverForwardedAndNeverCrashesIt) {
  start(profile_text(0, 0.01, 0, 0, 0), 3);
  driver_->publish_state(1);
  const auto wall_start = std::chrono::steady_clock::now();
  const int rounds = 200;
  for (int i = 0; i < rounds; ++i) {
    auto nan_packet = packet(0, 1000 + i, {0, 1});
    nan_packet.commands[0].vx = std::nan("");
    driver_->send(0, nan_packet);  // robot 1 goes on, robot 0 does not
    auto absurd = packet(0, 2000 + i, {2});
    absurd.commands[0].omega = 1e6;
    driver_->send(0, absurd);                       // nothing left: not forwarded
    driver_->send(0, packet(1, 3000 + i, {0}));     // blue's team field on the yellow channel
    driver_->send(0, packet(5, 4000 + i, {0}));     // no such team
    driver_->send(0, packet(0, 5000 + i, {2, 2}));  // robot 2 twice
    driver_->send(0, packet(0, 6000 + i, {42}));    // not on the field
    const std::vector<std::uint8_t> garbage{1, 2, 3, 4, 5, 6, 7};
    driver_->publish_raw(ubersim::channel_name(driver_->channels(),
                                               ubersim::topics::kRadio.of(ubersim::Team::Yellow)),
                         garbage);
    driver_->publish_raw(ubersim::channel_name(driver_->channels(), ubersim::topics::kSimState),
                         garbage);
    // A well-formed header claiming -1 commands (used to throw out of LCM's decode).
    auto negative = packet(0, 7000 + i, {});
    std::vector<std::uint8_t> bytes(negative.getEncodedSize());
    negative.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    std::fill(bytes.end() - 4, bytes.end(), 0xff);
    driver_->publish_raw(ubersim::channel_name(driver_->channels(),
                                               ubersim::topics::kRadio.of(ubersim::Team::Yellow)),
                         bytes);
    if (i % 20 == 0) {
      ASSERT_TRUE(driver_->sync()) << "the emulator stopped answering";
    }
  }
  ASSERT_TRUE(driver_->sync());
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  ASSERT_TRUE(process_->running());

  const auto& forwarded = driver_->commands(0);
  ASSERT_EQ(forwarded.size(), static_cast<std::size_t>(rounds));  // only the NaN packets' rest
  for (const auto& m : forwarded) {
    EXPECT_GE(m.sequence, 1000);
    EXPECT_LT(m.sequence, 2000);
    ASSERT_EQ(m.num_commands, 1);
    EXPECT_EQ(m.commands[0].robot_id, 1);
    EXPECT_TRUE(std::isfinite(m.commands[0].vx));
  }

  // Stop it and read its report and its log.
  EXPECT_EQ(process_->stop(), 0);
  const std::string log = process_->log();
  process_.reset();
  for (const char* counted :
       {"NaN/Inf: 200", "absurd value: 200", "team does not match channel: 200",
        "unknown team: 200", "duplicate robot id: 200", "robot not on the field: 200"}) {
    EXPECT_NE(log.find(counted), std::string::npos) << counted << "\n" << log;
  }
  EXPECT_NE(log.find("malformed LCM messages dropped: 600"), std::string::npos) << log;
  // At most one line per kind per second of the run (+1 for the first).
  const int allowed = static_cast<int>(std::ceil(wall_s)) + 1;
  for (const char* kind : {"NaN/Inf", "absurd value", "does not decode as radio_packet_t",
                           "does not decode as sim_state_t"}) {
    int lines = 0;
    std::istringstream text(log);
    for (std::string line; std::getline(text, line);)
      if (line.find("[warning]") != std::string::npos && line.find(kind) != std::string::npos)
        ++lines;
    EXPECT_GE(lines, 1) << kind;
    EXPECT_LE(lines, allowed) << kind << " in " << wall_s << " s\n" << log;
  }
}

TEST_F(RadioProcessTest, ExitsCleanlyOnSigterm) {
  start(profile_text(60, 0.03, 0, 0, 0), 1);
  EXPECT_TRUE(process_->running());
  EXPECT_EQ(process_->stop(), 0);
  process_.reset();
}
