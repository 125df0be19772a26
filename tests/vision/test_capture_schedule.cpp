// Capture instants phase-locked to sim time, served by physics steps.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "ubersim/vision/capture_schedule.hpp"

using ubersim::vision::CaptureSchedule;

namespace {

constexpr double kDt = 1.0 / 240;

struct Served {
  std::int64_t step;
  std::int64_t frame_number;
};

std::vector<Served> run(CaptureSchedule& schedule, std::int64_t first, std::int64_t last,
                        double dt = kDt) {
  std::vector<Served> served;
  for (std::int64_t step = first; step <= last; ++step) {
    if (const auto capture = schedule.on_state(static_cast<double>(step) * dt)) {
      served.push_back({step, capture->frame_number});
    }
  }
  return served;
}

}  // namespace

TEST(CaptureSchedule, ThirtyHertzOnEveryEighthStep) {
  CaptureSchedule schedule(30, 0);
  const auto served = run(schedule, 0, 2399);  // 10 s
  ASSERT_EQ(served.size(), 300u);
  for (std::size_t i = 0; i < served.size(); ++i) {
    EXPECT_EQ(served[i].step, static_cast<std::int64_t>(8 * i));
    EXPECT_EQ(served[i].frame_number, static_cast<std::int64_t>(i));
  }
}

TEST(CaptureSchedule, PhaseWrittenInDecimalStillLandsOnItsStep) {
  CaptureSchedule schedule(80, 0.0041667);  // one 240 Hz step, rounded
  const auto served = run(schedule, 0, 30);
  ASSERT_GE(served.size(), 3u);
  EXPECT_EQ(served[0].step, 1);
  EXPECT_EQ(served[1].step, 4);
  EXPECT_EQ(served[2].step, 7);
}

TEST(CaptureSchedule, InstantBetweenStepsIsServedByTheNextStep) {
  CaptureSchedule schedule(70, 0.001);  // neither divides the 240 Hz step
  const auto served = run(schedule, 0, 2400);
  ASSERT_GT(served.size(), 690u);
  for (const Served& s : served) {
    const double instant = 0.001 + static_cast<double>(s.frame_number) / 70;
    const double t = static_cast<double>(s.step) * kDt;
    EXPECT_GE(t, instant - CaptureSchedule::kTolerance);
    EXPECT_LT(t - kDt, instant);  // the first step at or after the instant
  }
}

TEST(CaptureSchedule, StartingLateCapturesFromTheNextInstantNumberedFromZero) {
  CaptureSchedule schedule(30, 0);
  const auto served = run(schedule, 243, 300);  // 1.0125 s: the 1.0333 s instant is next
  ASSERT_FALSE(served.empty());
  EXPECT_EQ(served[0].step, 248);
  EXPECT_EQ(served[0].frame_number, 0);
  EXPECT_EQ(served[1].frame_number, 1);
}

TEST(CaptureSchedule, LostStatesLeaveAGapInFrameNumbers) {
  CaptureSchedule schedule(30, 0);
  ASSERT_TRUE(schedule.on_state(0.0));
  // States up to 0.1 s never arrived: the instants at 1/30 and 2/30 s passed unserved.
  const auto capture = schedule.on_state(0.1);
  ASSERT_TRUE(capture);
  EXPECT_EQ(capture->missed_instants, 2);
  EXPECT_EQ(capture->frame_number, 3);
  EXPECT_FALSE(schedule.on_state(0.1 + kDt));
}

TEST(CaptureSchedule, RestartFollowsTheNewTimelineAndKeepsNumbering) {
  CaptureSchedule schedule(30, 0);
  const auto before = run(schedule, 0, 100);  // frames 0..12
  ASSERT_EQ(before.back().frame_number, 12);
  schedule.restart();
  const auto after = run(schedule, 0, 16);
  ASSERT_EQ(after.size(), 3u);
  EXPECT_EQ(after[0].step, 0);
  EXPECT_EQ(after[0].frame_number, 13);
  EXPECT_EQ(after[2].frame_number, 15);
}
