// The state the bridge acts on (radio t_sent, tracked latency, teleports):
// only a SIM_STATE with a sim time physics could have sent replaces it.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "ubersim/ssl_bridge/latest_state.hpp"

using ubersim::sim_state_t;
using ubersim::ssl::LatestState;

TEST(SslLatestState, OnlyAStateWithAValidSimTimeIsKept) {
  LatestState latest;
  EXPECT_EQ(latest.get(), nullptr);
  EXPECT_EQ(latest.sim_time(), 0.0);  // radio t_sent before any state
  sim_state_t state{};
  state.sim_time = 1.5;
  state.step = 360;
  EXPECT_TRUE(latest.update(state));
  ASSERT_NE(latest.get(), nullptr);
  EXPECT_EQ(latest.sim_time(), 1.5);

  for (double bad :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
        -std::numeric_limits<double>::infinity(), -0.25, ubersim::SimClock::kMaxSimTime * 1.000001,
        1.6e39}) {
    sim_state_t hostile = state;
    hostile.sim_time = bad;
    hostile.step = 361;
    EXPECT_FALSE(latest.update(hostile)) << bad;
    EXPECT_EQ(latest.sim_time(), 1.5) << "kept after " << bad;
    EXPECT_EQ(latest.get()->step, 360);
  }
  EXPECT_EQ(latest.refused(), 6u);

  state.sim_time = 0.0;  // physics reset: a valid time, even if earlier
  state.step = 0;
  EXPECT_TRUE(latest.update(state));
  EXPECT_EQ(latest.sim_time(), 0.0);
  state.sim_time = ubersim::SimClock::kMaxSimTime;
  EXPECT_TRUE(latest.update(state));
  EXPECT_EQ(latest.refused(), 6u);
}
