// Sync mode's bookkeeping in the radio emulator (docs/sync.md): clients,
// frames owed, answers matched to frames, timeouts; and the command link's
// earliest t_apply, which with the answers gives physics its horizon.
#include <gtest/gtest.h>

#include <ubersim/team_t.hpp>

#include "radio_test_util.hpp"
#include "ubersim/radio/command_link.hpp"
#include "ubersim/radio/sync_coordinator.hpp"

using ubersim::Team;
using ubersim::radio::CommandLink;
using ubersim::radio::SyncCoordinator;
using Clock = SyncCoordinator::Clock;

namespace {

ubersim::sync_client_t client(int team, const std::string& name, bool leaving = false) {
  ubersim::sync_client_t m{};
  m.team = static_cast<std::int8_t>(team);
  m.name = name;
  m.leaving = leaving;
  return m;
}

// Frames captured at `captures`, published at t_state; next frame at `next`.
ubersim::vision_schedule_t schedule(double t_state, std::int64_t step, std::vector<double> captures,
                                    double next) {
  ubersim::vision_schedule_t s{};
  s.t_state = t_state;
  s.step = step;
  s.next_publication = next;
  s.next_capture = next;
  s.num_frames = static_cast<std::int32_t>(captures.size());
  for (std::size_t i = 0; i < captures.size(); ++i) {
    s.camera_id.push_back(0);
    s.frame_number.push_back(static_cast<std::int64_t>(i));
    s.t_capture.push_back(captures[i]);
  }
  return s;
}

}  // namespace

TEST(SyncCoordinator, AnswerArrivesWhenItsFrameWasPublished) {
  SyncCoordinator sync(1.0);
  const auto now = Clock::now();
  EXPECT_FALSE(sync.on_client(client(0, "a")).empty());
  EXPECT_EQ(sync.earliest_arrival(Team::Yellow), SyncCoordinator::kInfinity)
      << "no vision heard yet";
  sync.on_schedule(schedule(0.0, 0, {}, 0.066), now);
  EXPECT_DOUBLE_EQ(sync.earliest_arrival(Team::Yellow), 0.066);
  EXPECT_FALSE(sync.bound_by(Team::Yellow).has_value()) << "waits for the next frame";
  sync.on_schedule(schedule(0.0666, 16, {0.0}, 0.1), now);
  EXPECT_DOUBLE_EQ(sync.earliest_arrival(Team::Yellow), 0.0666) << "owes the frame";
  EXPECT_EQ(sync.bound_by(Team::Yellow), "a");
  const auto answer = sync.on_answer(Team::Yellow, 0.0, now);
  EXPECT_EQ(answer.verdict, SyncCoordinator::Verdict::Accepted);
  EXPECT_DOUBLE_EQ(answer.t_arrival, 0.0666);
  EXPECT_DOUBLE_EQ(sync.earliest_arrival(Team::Yellow), 0.1);
  EXPECT_EQ(sync.earliest_arrival(Team::Blue), SyncCoordinator::kInfinity) << "no blue client";
}

TEST(SyncCoordinator, DuplicatesOutOfOrderAndUnregisteredAnswersAreCountedAndIgnored) {
  SyncCoordinator sync(1.0);
  const auto now = Clock::now();
  sync.on_client(client(0, "a"));
  sync.on_schedule(schedule(0.1, 24, {0.0}, 0.13), now);
  sync.on_schedule(schedule(0.13, 32, {0.033}, 0.16), now);
  EXPECT_EQ(sync.on_answer(Team::Blue, 0.0, now).verdict, SyncCoordinator::Verdict::Unregistered);
  // Answering the later frame first skips the earlier one (nothing to send for it)...
  EXPECT_EQ(sync.on_answer(Team::Yellow, 0.033, now).verdict, SyncCoordinator::Verdict::Accepted);
  // ...so the earlier one's answer now comes out of order, and a repeat is a duplicate.
  EXPECT_EQ(sync.on_answer(Team::Yellow, 0.0, now).verdict, SyncCoordinator::Verdict::Unmatched);
  EXPECT_EQ(sync.on_answer(Team::Yellow, 0.033, now).verdict, SyncCoordinator::Verdict::Unmatched);
  EXPECT_EQ(sync.stats().unregistered, 1u);
  EXPECT_EQ(sync.stats().unmatched, 2u);
  EXPECT_EQ(sync.client_stats().at(0).frames_skipped, 1u);
}

TEST(SyncCoordinator, OneClientPerTeamAndLeaving) {
  SyncCoordinator sync(1.0);
  sync.on_client(client(1, "first"));
  EXPECT_NE(sync.on_client(client(1, "second")).find("refused"), std::string::npos);
  EXPECT_EQ(sync.on_client(client(1, "first")), "") << "the periodic repetition";
  EXPECT_EQ(sync.clients(), 1);
  sync.on_client(client(1, "first", true));
  EXPECT_EQ(sync.clients(), 0);
  EXPECT_EQ(sync.stats().refused, 1u);
}

TEST(SyncCoordinator, ClientPastTheTimeoutIsDropped) {
  SyncCoordinator sync(0.5);
  const auto start = Clock::now();
  sync.on_client(client(0, "slow"));
  sync.on_schedule(schedule(0.1, 24, {0.0}, 0.13), start);
  EXPECT_TRUE(sync.expire(start + std::chrono::milliseconds(400)).empty());
  const auto dropped = sync.expire(start + std::chrono::milliseconds(600));
  ASSERT_EQ(dropped.size(), 1u);
  EXPECT_EQ(dropped[0].client, "slow");
  EXPECT_DOUBLE_EQ(dropped[0].t_sim, 0.1) << "its unanswered frame's publication";
  EXPECT_NE(dropped[0].describe().find("sync client dropped: team yellow, client 'slow', at sim "
                                       "time 0.100 s"),
            std::string::npos)
      << dropped[0].describe();
  EXPECT_EQ(sync.clients(), 0);
  EXPECT_EQ(sync.stats().timeouts, 1u);
  EXPECT_EQ(sync.earliest_arrival(Team::Yellow), SyncCoordinator::kInfinity);
}

TEST(SyncCoordinator, DroppedTeamIsWithoutControlUntilItsClientRejoins) {
  SyncCoordinator sync(0.5);
  const auto start = Clock::now();
  sync.on_client(client(1, "blue\nfake line"));
  sync.on_schedule(schedule(2.0, 480, {1.97}, 2.03), start);
  EXPECT_EQ(sync.summary(), "sync: no client was dropped");
  ASSERT_EQ(sync.expire(start + std::chrono::seconds(1)).size(), 1u);
  EXPECT_EQ(sync.control(Team::Blue).client, "blue?fake line") << "one line in the log";
  EXPECT_DOUBLE_EQ(sync.control(Team::Blue).dropped_at, 2.0);
  EXPECT_EQ(sync.status().drops[1], 1);
  // Physics runs on without it; then it registers again.
  sync.on_schedule(schedule(5.5, 1320, {5.47}, 5.53), start + std::chrono::seconds(2));
  EXPECT_NE(sync.summary().find("blue without control for 3.500 s of sim time (1 drop of client "
                                "'blue?fake line', not back by the end)"),
            std::string::npos)
      << sync.summary();
  const std::string rejoined = sync.on_client(client(1, "blue"));
  EXPECT_EQ(rejoined,
            "sync client rejoined: team blue, client 'blue', at sim time 5.500 s, after 3.500 s of "
            "sim time without control");
  EXPECT_DOUBLE_EQ(sync.control(Team::Blue).without_control_until(9.0), 3.5);
  EXPECT_LT(sync.status().dropped_at[1], 0);
  EXPECT_DOUBLE_EQ(sync.status().without_control[1], 3.5);
  EXPECT_EQ(sync.status().drops[0], 0) << "yellow had no client to lose";
}

TEST(SyncCoordinator, OwnStallDoesNotCountAgainstTheClients) {
  SyncCoordinator sync(0.5);
  const auto start = Clock::now();
  sync.on_client(client(0, "a"));
  sync.on_schedule(schedule(0.1, 24, {0.0}, 0.13), start);
  sync.forgive(std::chrono::milliseconds(800));  // the radio emulator itself did not run
  EXPECT_TRUE(sync.expire(start + std::chrono::milliseconds(1200)).empty());
  EXPECT_EQ(sync.expire(start + std::chrono::milliseconds(1400)).size(), 1u);
}

TEST(CommandLinkHorizon, EarliestApplyIsExactlyTheNextPacketsTApply) {
  // Jitter drawn ahead: the bound is the t_apply the packet then really gets.
  CommandLink link(radio_test::profile(60, 0.033, 0.002), Team::Yellow, 3);
  double arrival = 0.1;
  for (int i = 0; i < 50; ++i, arrival += 1.0 / 30) {
    const double bound = link.earliest_apply(arrival);
    const auto out = link.offer(radio_test::packet(0, i, {0}), arrival);
    ASSERT_TRUE(out.has_value());
    EXPECT_EQ(out->t_apply, bound) << "packet " << i;
    EXPECT_GT(out->t_apply, arrival + 0.02);
  }
  EXPECT_EQ(link.earliest_apply(SyncCoordinator::kInfinity), SyncCoordinator::kInfinity);
}

TEST(CommandLinkHorizon, BusyLinkBoundsByWhenItFrees) {
  CommandLink link(radio_test::profile(10, 0.0), Team::Yellow, 1);  // busy 0.1 s per packet
  ASSERT_TRUE(link.offer(radio_test::packet(0, 1, {0}), 0.0));
  EXPECT_DOUBLE_EQ(link.earliest_apply(0.01), 0.1) << "the next can go out at 0.1 s";
  EXPECT_FALSE(link.offer(radio_test::packet(0, 2, {0}), 0.05));  // waits for the link
  EXPECT_DOUBLE_EQ(link.earliest_apply(SyncCoordinator::kInfinity), 0.1);
}

TEST(SyncCoordinator, RepeatedScheduleAnnouncesNoFrameTwice) {
  SyncCoordinator sync(1.0);
  const auto now = Clock::now();
  sync.on_client(client(0, "a"));
  sync.on_schedule(schedule(0.0, 0, {0.0}, 0.033), now);
  EXPECT_EQ(sync.on_answer(Team::Yellow, 0.0, now).verdict, SyncCoordinator::Verdict::Accepted);
  sync.on_schedule(schedule(0.0, 0, {0.0}, 0.033), now);  // the same step again
  EXPECT_DOUBLE_EQ(sync.earliest_arrival(Team::Yellow), 0.033) << "owes nothing";
  EXPECT_EQ(sync.stats().frames, 1u);
}

// A timed client (a team under the time shim, docs/sync.md "Timed clients"):
// its packets arrive at their own t_sent, an empty one is a promise, and it is
// dropped only when its promise stops short of the next frame for too long.
TEST(SyncCoordinator, TimedClientArrivesAtItsSendTimeAndIsHeldByItsPromise) {
  SyncCoordinator sync(1.0);
  const auto now = Clock::now();
  auto timed = client(0, "shim_yellow");
  timed.timed = true;
  EXPECT_FALSE(sync.on_client(timed).empty());
  sync.on_schedule(schedule(0.0, 0, {}, 0.05), now);
  EXPECT_DOUBLE_EQ(sync.earliest_arrival(Team::Yellow), 0.0) << "promised nothing yet";
  EXPECT_EQ(sync.bound_by(Team::Yellow), "shim_yellow");
  // A command sent at 20 ms arrives then, whatever frames were published.
  auto answer = sync.on_answer(Team::Yellow, 0.02, now);
  EXPECT_EQ(answer.verdict, SyncCoordinator::Verdict::Accepted);
  EXPECT_DOUBLE_EQ(answer.t_arrival, 0.02);
  EXPECT_DOUBLE_EQ(sync.earliest_arrival(Team::Yellow), 0.02);
  // Frames owe it nothing: a promise up to the next frame lets the run past it.
  sync.on_schedule(schedule(0.05, 12, {0.0}, 0.07), now);
  EXPECT_DOUBLE_EQ(sync.earliest_arrival(Team::Yellow), 0.02);
  EXPECT_EQ(sync.on_answer(Team::Yellow, 0.07, now).verdict, SyncCoordinator::Verdict::Accepted);
  EXPECT_FALSE(sync.bound_by(Team::Yellow).has_value()) << "waits for the next frame";
  EXPECT_EQ(sync.on_answer(Team::Yellow, 0.06, now).verdict, SyncCoordinator::Verdict::Unmatched)
      << "earlier than its promise";
  EXPECT_TRUE(sync.expire(now + std::chrono::seconds(5)).empty()) << "it kept up: no drop";
  // The next frame is ahead of its promise, and it does not advance: dropped.
  sync.on_schedule(schedule(0.07, 17, {0.05}, 0.09), now);
  EXPECT_TRUE(sync.expire(now + std::chrono::milliseconds(900)).empty());
  const auto dropped = sync.expire(now + std::chrono::milliseconds(1100));
  ASSERT_EQ(dropped.size(), 1u);
  EXPECT_DOUBLE_EQ(dropped[0].t_sim, 0.07);
  EXPECT_NE(dropped[0].describe().find("sync client dropped: team yellow, client 'shim_yellow', "
                                       "at sim time 0.070 s: its time did not advance"),
            std::string::npos)
      << dropped[0].describe();
}
