// Sync mode through the bridge: which frame a team's RobotControl answers.
#include <gtest/gtest.h>

#include "ubersim/ssl_bridge/sync_answers.hpp"

using ubersim::ssl::SyncAnswers;
using Kind = SyncAnswers::Kind;

namespace {

const SyncAnswers::Clock::time_point t0{};

SyncAnswers::Clock::time_point at(double seconds) {
  return t0 + std::chrono::duration_cast<SyncAnswers::Clock::duration>(
                  std::chrono::duration<double>(seconds));
}

}  // namespace

TEST(SyncAnswers, FirstDatagramRegistersThenEachAnswersTheOldestFrame) {
  SyncAnswers team(1.0);
  team.on_frame(0.0, t0);  // before the hello: not the team's to answer
  EXPECT_FALSE(team.registered());
  EXPECT_EQ(team.on_datagram().kind, Kind::Registered);
  EXPECT_TRUE(team.registered());
  EXPECT_EQ(team.owed(), 0u);

  // Two cameras captured at the same instant: two frames, two answers.
  team.on_frame(0.1, t0);
  team.on_frame(0.1, t0);
  team.on_frame(0.2, t0);
  for (double expected : {0.1, 0.1, 0.2}) {
    const auto d = team.on_datagram();
    ASSERT_EQ(d.kind, Kind::Answer);
    EXPECT_EQ(d.t_capture, expected);
  }
  // Nothing owed: an extra datagram is counted and answers nothing.
  EXPECT_EQ(team.on_datagram().kind, Kind::Extra);
  team.on_frame(0.3, t0);
  EXPECT_EQ(team.on_datagram().t_capture, 0.3);
  EXPECT_EQ(team.stats().frames, 4u);
  EXPECT_EQ(team.stats().answers, 4u);
  EXPECT_EQ(team.stats().extra, 1u);
}

TEST(SyncAnswers, ASilentTeamIsDroppedAfterTheTimeoutAndRegistersAgain) {
  SyncAnswers team(1.0);
  team.on_datagram();
  team.on_frame(0.1, at(0));
  team.on_frame(0.2, at(0.5));
  EXPECT_FALSE(team.expire(at(1.0)));  // the oldest waited exactly the timeout
  EXPECT_TRUE(team.expire(at(1.01)));
  EXPECT_FALSE(team.registered());
  EXPECT_EQ(team.owed(), 0u);
  EXPECT_EQ(team.stats().timeouts, 1u);
  team.on_frame(0.3, at(1.1));  // not owed while dropped
  EXPECT_EQ(team.on_datagram().kind, Kind::Registered);
  team.on_frame(0.4, at(1.2));
  EXPECT_EQ(team.on_datagram().t_capture, 0.4);
}

TEST(SyncAnswers, OwingTooManyFramesDropsTheTeam) {
  SyncAnswers team(1e9);
  team.on_datagram();
  for (std::size_t i = 0; i < SyncAnswers::kMaxOwed; ++i) {
    ASSERT_FALSE(team.on_frame(static_cast<double>(i), t0));
  }
  EXPECT_TRUE(team.on_frame(1e6, t0));
  EXPECT_FALSE(team.registered());
  EXPECT_EQ(team.owed(), 0u);
  EXPECT_EQ(team.stats().overflows, 1u);
}
