#include <gtest/gtest.h>

#include <limits>

#include "ubersim/delay_line.hpp"
#include "ubersim/sim_clock.hpp"

using ubersim::SimClock;

TEST(SimClock, AdvancesRejectsStaleAndDetectsReset) {
  SimClock clock;
  EXPECT_FALSE(clock.started());
  EXPECT_EQ(clock.update(0.0, 0), SimClock::Update::Advanced);
  EXPECT_EQ(clock.update(1.0, 240), SimClock::Update::Advanced);
  EXPECT_EQ(clock.update(0.5, 120), SimClock::Update::Rejected);  // out of order
  EXPECT_DOUBLE_EQ(clock.now(), 1.0);
  EXPECT_EQ(clock.update(std::numeric_limits<double>::quiet_NaN(), 241),
            SimClock::Update::Rejected);
  EXPECT_EQ(clock.update(-1.0, 241), SimClock::Update::Rejected);
  EXPECT_EQ(clock.update(SimClock::kMaxSimTime * 2, 241), SimClock::Update::Rejected);
  EXPECT_DOUBLE_EQ(clock.now(), 1.0);
  EXPECT_EQ(clock.update(0.0, 0), SimClock::Update::Reset);
  EXPECT_DOUBLE_EQ(clock.now(), 0.0);
  EXPECT_EQ(clock.update(1.0 / 240, 1), SimClock::Update::Advanced);
  EXPECT_TRUE(SimClock::valid_time(0.0));
  EXPECT_TRUE(SimClock::valid_time(SimClock::kMaxSimTime));
  EXPECT_FALSE(SimClock::valid_time(-1e-9));
  EXPECT_FALSE(SimClock::valid_time(std::numeric_limits<double>::infinity()));
}

TEST(DelayLine, ReleasesInOrderAtTheirTime) {
  ubersim::DelayLine<int> line;
  line.push(1.0, 1);
  line.push(1.5, 2);
  EXPECT_DOUBLE_EQ(line.push(1.2, 3), 1.5);  // jitter cannot overtake
  EXPECT_TRUE(line.pop_due(0.99).empty());
  auto due = line.pop_due(1.0);
  ASSERT_EQ(due.size(), 1u);
  EXPECT_EQ(due[0].second, 1);
  due = line.pop_due(2.0);
  ASSERT_EQ(due.size(), 2u);
  EXPECT_EQ(due[0].second, 2);
  EXPECT_EQ(due[1].second, 3);
  EXPECT_TRUE(line.empty());
}
