// Which states physics publishes with --truth-on-demand (docs/sync.md): the
// first step at or after every demanded instant, periodic or explicit; late
// instants are counted and served by the next state; silent consumers go.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "ubersim/physics/truth_demand.hpp"

using ubersim::physics::TruthDemand;

namespace {

constexpr double kDt = 1.0 / 240;

ubersim::truth_demand_t demand(const std::string& name, std::vector<double> period,
                               std::vector<double> phase, std::vector<double> instants) {
  ubersim::truth_demand_t d{};
  d.consumer = name;
  d.num_periodic = static_cast<std::int32_t>(period.size());
  d.period = std::move(period);
  d.phase = std::move(phase);
  d.num_instants = static_cast<std::int32_t>(instants.size());
  d.instants = std::move(instants);
  return d;
}

// Steps 1..steps; the steps (by index) whose state is wanted.
std::vector<int> wanted_steps(TruthDemand& demand, int steps) {
  std::vector<int> out;
  for (int i = 1; i <= steps; ++i) {
    if (demand.wanted(i * kDt, kDt)) {
      out.push_back(i);
      demand.published(i * kDt);
    }
  }
  return out;
}

}  // namespace

TEST(TruthDemand, PeriodicAndExplicitInstantsAreServedByTheFirstStepAtOrAfter) {
  TruthDemand truth;
  const auto now = TruthDemand::Clock::now();
  // 30 Hz from 0 (every 8th step) and one instant between steps 10 and 11.
  ASSERT_EQ(truth.on_demand(demand("vision", {1.0 / 30}, {0.0}, {10.5 * kDt}), 0, kDt, now), "");
  EXPECT_EQ(wanted_steps(truth, 24), (std::vector<int>{8, 11, 16, 24}));
  EXPECT_EQ(truth.late(), 0u);
}

TEST(TruthDemand, ARepeatedDemandIsNotLateButANewPastInstantIs) {
  TruthDemand truth;
  const auto now = TruthDemand::Clock::now();
  truth.on_demand(demand("vision", {}, {}, {3 * kDt}), 0, kDt, now);
  EXPECT_EQ(wanted_steps(truth, 5), (std::vector<int>{3}));
  // The consumer repeats an instant already served: not late.
  truth.on_demand(demand("vision", {}, {}, {3 * kDt}), 5 * kDt, kDt, now);
  EXPECT_EQ(truth.late(), 0u);
  // An instant physics passed without a state: late, and the next state is sent.
  truth.on_demand(demand("vision", {}, {}, {4 * kDt}), 5 * kDt, kDt, now);
  EXPECT_EQ(truth.late(), 1u);
  EXPECT_TRUE(truth.wanted(6 * kDt, kDt));
}

TEST(TruthDemand, SilentConsumersAreForgottenAndBadDemandsRefused) {
  TruthDemand truth;
  const auto start = TruthDemand::Clock::now();
  truth.on_demand(demand("viewer", {1.0 / 60}, {0.0}, {}), 0, kDt, start);
  EXPECT_NE(truth.on_demand(demand("x", {0.0}, {0.0}, {}), 0, kDt, start), "");
  EXPECT_NE(truth.on_demand(demand("", {}, {}, {}), 0, kDt, start), "");
  auto bad = demand("y", {}, {}, {1.0});
  bad.num_instants = 5;  // more than the array holds
  EXPECT_NE(truth.on_demand(bad, 0, kDt, start), "");
  EXPECT_EQ(truth.consumers(), 1u);
  EXPECT_TRUE(truth.expire(start + std::chrono::seconds(2), std::chrono::seconds(3)).empty());
  EXPECT_EQ(truth.expire(start + std::chrono::seconds(4), std::chrono::seconds(3)).size(), 1u);
  EXPECT_TRUE(truth.empty());
}

// Physics looks ahead with would_want() to sleep until the step of the next
// wanted state: it must give wanted()'s answer for every step, and change nothing.
TEST(TruthDemand, WouldWantForeseesWantedWithoutChangingIt) {
  TruthDemand truth;
  const auto now = TruthDemand::Clock::now();
  ASSERT_EQ(
      truth.on_demand(demand("vision", {1.0 / 30}, {0.0}, {10.5 * kDt, 13 * kDt}), 0, kDt, now),
      "");
  ASSERT_EQ(truth.on_demand(demand("radio", {1.0 / 20}, {0.02}, {}), 0, kDt, now), "");
  std::vector<int> foreseen, wanted;
  for (int i = 1; i <= 48; ++i) {
    // Looking ahead several steps (as physics does) does not consume anything.
    for (int k = 1; k <= 12; ++k) static_cast<void>(truth.would_want((i + k) * kDt, kDt));
    if (truth.would_want(i * kDt, kDt)) foreseen.push_back(i);
    if (truth.wanted(i * kDt, kDt)) {
      wanted.push_back(i);
      truth.published(i * kDt);
    }
  }
  EXPECT_EQ(foreseen, wanted);
  // 30 Hz: 8, 16, ...; 20 Hz from 0.02 s: 5, 17, 29, 41; instants: 11, 13.
  EXPECT_EQ(wanted, (std::vector<int>{5, 8, 11, 13, 16, 17, 24, 29, 32, 40, 41, 48}));
}
