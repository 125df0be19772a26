// Which states physics publishes (docs/sync.md, "Ground truth on demand"): the
// first step at or after every demanded instant, periodic or explicit; late
// instants are counted and served by the next state; silent consumers go;
// physics' own consumers (every step, while nobody asks, the referee's) are
// demands like the programs'.
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
  EXPECT_EQ(truth.programs(), 1u);
  EXPECT_TRUE(truth.expire(start + std::chrono::seconds(2), std::chrono::seconds(3)).empty());
  EXPECT_EQ(truth.expire(start + std::chrono::seconds(4), std::chrono::seconds(3)).size(), 1u);
  EXPECT_EQ(truth.programs(), 0u);
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

// Physics' own default publication (every step, or STATE_PUBLISH_RATE) is a
// consumer that counts only while no program asks; it is never forgotten.
TEST(TruthDemand, WhatPhysicsPublishesWhileNobodyAsksStopsWhileAProgramAsks) {
  TruthDemand truth;
  const auto start = TruthDemand::Clock::now();
  // 80 Hz at 240 Hz: every third step, served by the step nearest n / 80.
  truth.own_periodic("rate", 1.0 / 80, -kDt / 2, TruthDemand::While::NobodyAsks);
  EXPECT_EQ(wanted_steps(truth, 9), (std::vector<int>{3, 6, 9}));
  ASSERT_EQ(truth.on_demand(demand("viewer", {}, {}, {10 * kDt}), 9 * kDt, kDt, start), "");
  EXPECT_EQ(wanted_steps(truth, 12), (std::vector<int>{10}));  // steps 1..12 again: only 10
  truth.expire(start + std::chrono::seconds(4), std::chrono::seconds(3));
  EXPECT_EQ(truth.programs(), 0u);
  EXPECT_EQ(wanted_steps(truth, 6), (std::vector<int>{3, 6}));
}

// --truth-every-step is a consumer that wants every step, whatever the rest
// want; a program cannot take the name of one of physics' own consumers.
TEST(TruthDemand, AnOwnEveryStepConsumerWinsOverARate) {
  TruthDemand truth;
  const auto start = TruthDemand::Clock::now();
  truth.own_periodic("rate", 1.0 / 80, -kDt / 2, TruthDemand::While::NobodyAsks);
  truth.own_every_step("every step", TruthDemand::While::Always);
  EXPECT_EQ(wanted_steps(truth, 4), (std::vector<int>{1, 2, 3, 4}));
  EXPECT_NE(truth.on_demand(demand("every step", {}, {}, {}), 0, kDt, start), "");
  EXPECT_EQ(truth.programs(), 0u);
  truth.forget("every step");
  EXPECT_EQ(wanted_steps(truth, 4), (std::vector<int>{3}));
}

// The referee's demand in sync mode: every state at or after the one it judges next.
TEST(TruthDemand, TheRefereesDemandIsEveryStateFromTheOneItJudgesNext) {
  TruthDemand truth;
  const auto start = TruthDemand::Clock::now();
  ASSERT_EQ(truth.on_demand(demand("vision", {}, {}, {2 * kDt}), 0, kDt, start), "");
  truth.own_from("referee", 4 * kDt);
  EXPECT_EQ(wanted_steps(truth, 6), (std::vector<int>{2, 4, 5, 6}));
  truth.reset();  // a reset keeps what physics' own consumers want
  EXPECT_EQ(wanted_steps(truth, 4), (std::vector<int>{4}));
}
