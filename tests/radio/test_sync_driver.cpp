// Sync mode in the radio emulator process (docs/sync.md), over a real bus
// (LCM's in-process memq://): the SyncDriver is handed the wall time of every
// call, so its timeouts, its own stalls and its repeats are checked here at
// given instants, without sleeping.
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <ubersim/sync_horizon_t.hpp>
#include <ubersim/sync_status_t.hpp>
#include <ubersim/truth_demand_t.hpp>
#include <vector>

#include "radio_test_util.hpp"
#include "ubersim/radio/sync_driver.hpp"
#include "ubersim/topics.hpp"

using ubersim::radio::SyncDriver;
using Clock = SyncDriver::Clock;
using std::chrono::milliseconds;

namespace {

ubersim::sync_client_t client(int team, const std::string& name) {
  ubersim::sync_client_t m{};
  m.team = static_cast<std::int8_t>(team);
  m.name = name;
  return m;
}

// One frame captured at 0 s, published at 0.1 s; the next at 0.13 s.
ubersim::vision_schedule_t first_frame() {
  ubersim::vision_schedule_t s{};
  s.t_state = 0.1;
  s.step = 24;
  s.next_publication = s.next_capture = 0.13;
  s.num_frames = 1;
  s.camera_id = {0};
  s.frame_number = {0};
  s.t_capture = {0.0};
  return s;
}

// A horizon's hold, typed reason and name: "registering", "next frame vision", "client a".
std::string hold_of(const ubersim::sync_horizon_t& h) {
  using ubersim::sync_horizon_t;
  switch (h.held_by) {
    case sync_horizon_t::HELD_BY_REGISTRATION:
      return "registering" + h.waiting_for;
    case sync_horizon_t::HELD_BY_NEXT_FRAME:
      return "next frame " + h.waiting_for;
    case sync_horizon_t::HELD_BY_CLIENT:
      return "client " + h.waiting_for;
    case sync_horizon_t::HELD_BY_FEEDBACK:
      return "feedback " + h.waiting_for;
    default:
      return "nothing" + h.waiting_for;
  }
}

// The driver of a yellow client ("a"), and what it says on the bus, in order:
// "horizon:<hold_of>", "status:<yellow drops>", "demand" (its before_release).
struct Rig {
  explicit Rig(bool strict) : emulator(profiles(), 1) {
    using namespace ubersim;
    subscribe(bus, channels, topics::kSyncHorizon, [this](const sync_horizon_t& h) {
      said.push_back("horizon:" + hold_of(h));
      horizon = h.horizon;
    });
    subscribe(bus, channels, topics::kSyncStatus, [this](const sync_status_t& s) {
      said.push_back("status:" + std::to_string(s.drops[0]));
    });
    subscribe(bus, channels, topics::kTruthDemand,
              [this](const truth_demand_t&) { said.push_back("demand"); });
    ubersim::radio::SyncOptions options;
    options.client_timeout = 0.5;
    options.strict = strict;
    options.expected_clients = 1;
    driver = std::make_unique<SyncDriver>(bus, channels, emulator, options,
                                          [this](const ubersim::radio::RadioEmulator::Output& out) {
                                            for (const auto& message : out.commands)
                                              forwarded.push_back(message);
                                          });
    driver->before_release(
        [this] { publish(bus, channels, ubersim::topics::kTruthDemand, emulator.truth_demand()); });
  }
  static std::array<ubersim::radio::RadioProfile, 2> profiles() {
    return {radio_test::profile(60, 0.033), radio_test::profile(60, 0.033)};
  }
  std::vector<std::string> heard() {
    said.clear();
    bus.handle_pending();
    return said;
  }

  ubersim::MessageBus bus{"memq://"};
  ubersim::ChannelNames channels;
  ubersim::radio::RadioEmulator emulator;
  std::unique_ptr<SyncDriver> driver;
  std::vector<std::string> said;
  std::vector<ubersim::sim_commands_t> forwarded;  // SIM_COMMANDS, in order
  double horizon = -1;                             // the latest published
};

}  // namespace

TEST(SyncDriver, HoldsUntilRegisteredAndAnnouncesTheDemandRightBeforeTheRelease) {
  Rig rig(false);
  const Clock::time_point t0 = Clock::now();
  ASSERT_TRUE(rig.driver->tick(t0));
  EXPECT_EQ(rig.heard(), (std::vector<std::string>{"status:0", "horizon:registering"}));
  ASSERT_TRUE(rig.driver->tick(t0 + milliseconds(50)));
  EXPECT_TRUE(rig.heard().empty()) << "nothing new, and less than 100 ms since the last horizon";
  ASSERT_TRUE(rig.driver->tick(t0 + milliseconds(100)));
  EXPECT_EQ(rig.heard(), (std::vector<std::string>{"horizon:registering"})) << "the repeat";
  rig.driver->on_client(client(0, "a"), t0 + milliseconds(120));
  EXPECT_EQ(rig.heard(),
            (std::vector<std::string>{"status:0", "demand", "horizon:next frame vision"}));
  rig.driver->on_schedule(first_frame(), t0 + milliseconds(130));
  EXPECT_EQ(rig.heard(), (std::vector<std::string>{"horizon:client a"})) << "once only: no demand";
}

TEST(SyncDriver, OwnStallIsForgivenAndAClientPastTheTimeoutDropped) {
  Rig rig(false);
  const Clock::time_point t0 = Clock::now();
  rig.driver->on_client(client(0, "a"), t0);
  rig.driver->on_schedule(first_frame(), t0);  // "a" owes the frame from t0
  ASSERT_TRUE(rig.driver->tick(t0 + milliseconds(100)));
  // No wakeup for 800 ms: this process did not run, so neither could the client.
  ASSERT_TRUE(rig.driver->tick(t0 + milliseconds(900)));
  ASSERT_TRUE(rig.driver->tick(t0 + milliseconds(1000)));
  ASSERT_TRUE(rig.driver->tick(t0 + milliseconds(1100)));
  rig.heard();
  ASSERT_TRUE(rig.driver->tick(t0 + milliseconds(1200))) << "0.4 s owed: in time";
  EXPECT_EQ(rig.heard(), (std::vector<std::string>{"horizon:client a"}));
  ASSERT_TRUE(rig.driver->tick(t0 + milliseconds(1350))) << "0.55 s owed: dropped, run goes on";
  // No client left: nothing bounds the horizon.
  EXPECT_EQ(rig.heard(), (std::vector<std::string>{"status:1", "horizon:nothing"}))
      << "the drop goes out before the horizon that lets physics past it";
}

TEST(SyncDriver, StrictFailsTheRunAtTheFirstDrop) {
  Rig rig(true);
  const Clock::time_point t0 = Clock::now();
  rig.driver->on_client(client(0, "a"), t0);
  rig.driver->on_schedule(first_frame(), t0);
  for (int ms = 100; ms <= 500; ms += 100) ASSERT_TRUE(rig.driver->tick(t0 + milliseconds(ms)));
  rig.heard();
  EXPECT_FALSE(rig.driver->tick(t0 + milliseconds(600)));
  EXPECT_TRUE(rig.heard().empty()) << "nothing more is said: the run stops";
}

// A timed client's start-up packet (sent at sim time 0) may come before
// physics' first state, on another socket: held, then checked against the
// robots that state names, never dropped as "robot not on the field" (which
// made reruns differ by which socket won).
TEST(SyncDriver, AnAnswerBeforeTheFirstStateIsCheckedWhenItComes) {
  Rig rig(false);
  const Clock::time_point t0 = Clock::now();
  ubersim::sync_client_t timed = client(0, "a");
  timed.timed = true;
  rig.driver->on_client(timed, t0);
  rig.driver->on_schedule(first_frame(), t0);
  rig.driver->on_packet(ubersim::Team::Yellow, radio_test::packet(0, 1, {0, 1}), t0);
  EXPECT_EQ(rig.emulator.report(ubersim::Team::Yellow).problem(ubersim::radio::Problem::OffField),
            0U);
  rig.driver->on_sim_state(radio_test::state(0, 0, 2), t0);
  const auto report = rig.emulator.report(ubersim::Team::Yellow);
  EXPECT_EQ(report.problem(ubersim::radio::Problem::OffField), 0U);
  EXPECT_EQ(report.problem(ubersim::radio::Problem::NoSimTime), 0U);
  // Promised to 0.2 s: the held packet, arrived at 0 s, goes out on a free link.
  ubersim::radio_packet_t promise = radio_test::packet(0, 2, {});
  promise.t_sent = 0.2;
  rig.driver->on_packet(ubersim::Team::Yellow, promise, t0);
  ASSERT_EQ(rig.forwarded.size(), 1U);
  EXPECT_EQ(rig.forwarded[0].num_commands, 2);
}

// A timed client's program gets the feedback at the sim time it was sent (the
// bridge hands it over in sim time), so physics waits at each state the
// feedback links must see (a sample, a delivery) until this radio saw it; the
// truth demand names the delivery, so physics publishes the state it waits at.
TEST(SyncDriver, WithATimedClientPhysicsWaitsForTheFeedbackLinks) {
  Rig rig(false);  // feedback at 30 Hz, delivered 0.02 s after its sample
  const Clock::time_point t0 = Clock::now();
  ubersim::sync_client_t timed = client(0, "a");
  timed.timed = true;
  rig.driver->on_client(timed, t0);
  rig.driver->on_schedule(first_frame(), t0);
  ubersim::radio_packet_t promise = radio_test::packet(0, 1, {});
  promise.t_sent = 0.5;
  rig.driver->on_packet(ubersim::Team::Yellow, promise, t0);
  rig.heard();
  EXPECT_EQ(rig.horizon, 0.0) << "no state seen yet: the first one is sampled";
  rig.driver->on_sim_state(radio_test::state(0, 0, 2), t0);
  EXPECT_EQ(rig.heard().back(), "horizon:feedback radio feedback");
  EXPECT_NEAR(rig.horizon, 0.02, 1e-9) << "the sample at 0 is delivered at 0.02";
  const ubersim::truth_demand_t demand = rig.emulator.truth_demand();
  ASSERT_EQ(demand.num_instants, 2);
  EXPECT_NEAR(demand.instants[0], 0.02, 1e-9);
  rig.driver->on_sim_state(radio_test::state(5.0 / 240, 5, 2), t0);
  rig.heard();
  EXPECT_NEAR(rig.horizon, 1.0 / 30, 1e-9) << "delivered; the next sample";
  rig.driver->on_client(
      [] {
        ubersim::sync_client_t leaving = client(0, "a");
        leaving.leaving = true;
        return leaving;
      }(),
      t0);
  rig.heard();
  EXPECT_GT(rig.horizon, 0.4) << "no timed client: the feedback holds nothing";
}
