// Tracked frames from ground truth, in-process: rate, delay like vision,
// kick detection and stop prediction.
#include <gtest/gtest.h>

#include <cmath>
#include <ubersim/team_t.hpp>

#include "ubersim/ssl_bridge/tracked_frames.hpp"

using namespace ubersim;
using namespace ubersim::ssl;

namespace {

sim_state_t state_at(double t, double ball_vx) {
  sim_state_t s{};
  s.sim_time = t;
  s.ball_present = true;
  s.ball.position[0] = 0.1 + ball_vx * 0.001;
  s.ball.position[1] = 0.5;
  s.ball.linear_velocity[0] = ball_vx;
  robot_state_t r{};
  r.team = team_t::YELLOW;
  r.robot_id = 5;
  r.x = 0.0;
  r.y = 0.5;
  s.robots.push_back(r);
  s.num_robots = 1;
  return s;
}

}  // namespace

TEST(SslTrackedFrames, FramesAtTheRateReleasedAfterTheVisionLatency) {
  TrackedSettings settings;
  settings.rate = 60;
  settings.uuid = make_uuid();
  TrackedFrames tracked(settings);
  tracked.set_latency(0.035);
  std::vector<TrackerWrapperPacket> out;
  for (int step = 0; step <= 240; ++step) {  // 1 s at 240 Hz
    const double t = step / 240.0;
    for (auto& p : tracked.on_state(state_at(t, 0))) {
      // Released no earlier than its timestamp plus the latency.
      EXPECT_GE(t + 1e-9, p.tracked_frame().timestamp() + 0.035);
      EXPECT_LT(t, p.tracked_frame().timestamp() + 0.035 + 1.0 / 240 + 1e-9);
      out.push_back(p);
    }
  }
  // 60 Hz over (1 - 0.035) s of releases.
  EXPECT_NEAR(static_cast<double>(out.size()), 0.965 * 60, 2.0);
  for (std::size_t i = 1; i < out.size(); ++i) {
    EXPECT_EQ(out[i].tracked_frame().frame_number(), out[i - 1].tracked_frame().frame_number() + 1);
    EXPECT_EQ(out[i].uuid(), settings.uuid);
  }
  EXPECT_EQ(settings.uuid.size(), 36u);
  EXPECT_EQ(settings.uuid[14], '4');
}

TEST(SslTrackedFrames, AKickNextToARobotIsTheKickedBallWithItsStop) {
  TrackedSettings settings;
  settings.rate = 240;
  settings.ball_model = BallModel{4.0, 0.5, 0.7};
  TrackedFrames tracked(settings);
  tracked.on_state(state_at(0.0, 0.0));
  auto frames = tracked.on_state(state_at(1.0 / 240, 4.0));  // 4 m/s in one step
  ASSERT_EQ(frames.size(), 1u);
  ASSERT_TRUE(frames[0].tracked_frame().has_kicked_ball());
  const KickedBall& k = frames[0].tracked_frame().kicked_ball();
  EXPECT_EQ(k.robot_id().id(), 5u);
  EXPECT_EQ(k.robot_id().team(), YELLOW);
  EXPECT_FLOAT_EQ(k.vel().x(), 4.0f);
  // Slide 4 -> 2.8 m/s at 4 m/s^2 (0.3 s, 1.02 m), roll 2.8 -> 0 at 0.5 m/s^2 (5.6 s, 7.84 m).
  EXPECT_NEAR(k.stop_timestamp() - k.start_timestamp(), 5.9, 1e-6);
  EXPECT_NEAR(k.stop_pos().x() - k.pos().x(), 8.86, 1e-4);
  // At rest again: no kicked ball any more.
  frames = tracked.on_state(state_at(2.0 / 240, 0.0));
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_FALSE(frames[0].tracked_frame().has_kicked_ball());
}

// Anyone on the bus may send SIM_STATE: a state with NaN or a number beyond
// 1e9 makes no tracked frame (SSL software is not written for NaN) and does
// not disturb the frames of the states around it.
TEST(SslTrackedFrames, AStateWithANumberNotFiniteOrHugeIsRefused) {
  TrackedSettings settings;
  settings.rate = 240;
  TrackedFrames tracked(settings);
  EXPECT_EQ(tracked.on_state(state_at(0, 0)).size(), 1u);
  sim_state_t bad = state_at(1.0 / 240, 0);
  bad.robots[0].omega = std::nan("");
  EXPECT_TRUE(tracked.on_state(bad).empty());
  bad = state_at(1.0 / 240, 0);
  bad.ball.linear_velocity[1] = 1e300;
  EXPECT_TRUE(tracked.on_state(bad).empty());
  bad = state_at(1e300, 0);
  EXPECT_TRUE(tracked.on_state(bad).empty());
  EXPECT_EQ(tracked.refused(), 3u);
  const auto next = tracked.on_state(state_at(1.0 / 240, 0));
  ASSERT_EQ(next.size(), 1u) << "the states around it are framed as before";
  EXPECT_EQ(next[0].tracked_frame().frame_number(), 1u);
}

TEST(SslSourceIds, ASeedGivesTheSameIdOnEveryRunAndEachPurposeItsOwn) {
  EXPECT_EQ(make_uuid(3, 1), make_uuid(3, 1));
  EXPECT_NE(make_uuid(3, 1), make_uuid(3, 2));
  EXPECT_NE(make_uuid(3, 1), make_uuid(4, 1));
  EXPECT_NE(make_uuid(std::uint64_t{1} << 40, 1), make_uuid(0, 1));  // the seed's high half counts
  EXPECT_NE(make_uuid(), make_uuid());  // no seed: random, as a real source's
  for (const std::string& id : {make_uuid(3, 1), make_uuid()}) {
    ASSERT_EQ(id.size(), 36U) << id;
    EXPECT_EQ(id[14], '4') << id;                                          // version 4
    EXPECT_NE(std::string("89ab").find(id[19]), std::string::npos) << id;  // variant 1
  }
}
