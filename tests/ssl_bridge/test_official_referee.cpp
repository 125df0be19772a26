// The official game controller's Referee -> REFEREE (referee_t): every field
// in SI units and sim time, game events of any type through their payloads,
// the ball in play once it moved 0.05 m after a restart, nothing NaN passed on.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <ubersim/team_t.hpp>

#include "ubersim/ssl_bridge/official_referee.hpp"

using namespace ubersim;

namespace {

Referee official(Referee::Command command, std::uint32_t counter) {
  Referee r;
  r.set_packet_timestamp(1'700'000'000'000'000ULL);  // the GC's wall clock: never used
  r.set_stage(Referee::NORMAL_FIRST_HALF);
  r.set_stage_time_left(123'500'000);
  r.set_command(command);
  r.set_command_counter(counter);
  r.set_command_timestamp(1'700'000'000'000'000ULL);
  for (Referee::TeamInfo* team : {r.mutable_yellow(), r.mutable_blue()}) {
    team->set_name("TIGERs Mannheim");
    team->set_score(0);
    team->set_red_cards(0);
    team->set_yellow_cards(0);
    team->set_timeouts(4);
    team->set_timeout_time(300'000'000);
    team->set_goalkeeper(0);
  }
  r.mutable_yellow()->set_score(2);
  r.mutable_yellow()->set_name("ER-Force");
  r.mutable_blue()->set_goalkeeper(7);
  r.mutable_blue()->set_foul_counter(3);
  r.set_blue_team_on_positive_half(true);
  return r;
}

sim_state_t state_with_ball(double t, double x, double y) {
  sim_state_t s{};
  s.sim_time = t;
  s.ball_present = true;
  s.ball.position[0] = x;
  s.ball.position[1] = y;
  return s;
}

}  // namespace

TEST(OfficialReferee, EveryFieldInSiUnitsAndSimTime) {
  ssl::OfficialRefereeTracker tracker;
  Referee in = official(Referee::BALL_PLACEMENT_BLUE, 5);
  in.mutable_designated_position()->set_x(1500);
  in.mutable_designated_position()->set_y(-250);
  in.set_next_command(Referee::DIRECT_FREE_BLUE);
  in.set_current_action_time_remaining(29'000'000);
  const sim_state_t state = state_with_ball(42.5, 0, 0);
  const referee_t out = tracker.translate(in, &state);
  EXPECT_DOUBLE_EQ(out.sim_time, 42.5);
  EXPECT_DOUBLE_EQ(out.command_time, 42.5);
  EXPECT_EQ(out.stage, +referee_t::STAGE_FIRST_HALF);
  EXPECT_DOUBLE_EQ(out.stage_time_left, 123.5);
  EXPECT_EQ(out.command, +referee_t::BALL_PLACEMENT_BLUE);
  EXPECT_EQ(out.command_counter, 5);
  ASSERT_TRUE(out.has_next_command);
  EXPECT_EQ(out.next_command, +referee_t::DIRECT_FREE_BLUE);
  EXPECT_DOUBLE_EQ(out.action_time_left, 29.0);
  ASSERT_TRUE(out.has_designated_position);
  EXPECT_DOUBLE_EQ(out.designated_position[0], 1.5);
  EXPECT_DOUBLE_EQ(out.designated_position[1], -0.25);
  EXPECT_TRUE(out.blue_on_positive_half);
  EXPECT_EQ(out.yellow_score, 2);
  EXPECT_EQ(out.blue_goalkeeper, 7);
  EXPECT_EQ(out.blue_fouls, 3);
  EXPECT_EQ(out.yellow_name, "ER-Force");  // the game controller's names, as it sends them
  EXPECT_EQ(out.blue_name, "TIGERs Mannheim");
  EXPECT_FALSE(out.game_over);
  in.set_stage(Referee::POST_GAME);
  EXPECT_TRUE(tracker.translate(in, &state).game_over);
}

TEST(OfficialReferee, BallInPlayOnceItMovedFiveCentimetresAfterTheRestart) {
  ssl::OfficialRefereeTracker tracker;
  const Referee free_kick = official(Referee::DIRECT_FREE_YELLOW, 9);
  sim_state_t s = state_with_ball(10.0, 1.0, 1.0);
  EXPECT_FALSE(tracker.translate(free_kick, &s).ball_in_play);
  s = state_with_ball(10.5, 1.04, 1.0);  // 4 cm: not yet
  EXPECT_FALSE(tracker.translate(free_kick, &s).ball_in_play);
  s = state_with_ball(10.6, 1.06, 1.0);
  const referee_t taken = tracker.translate(free_kick, &s);
  EXPECT_TRUE(taken.ball_in_play);
  EXPECT_DOUBLE_EQ(taken.command_time, 10.0);  // when the command first came
  // The next command starts over; FORCE_START puts the ball in play at once.
  EXPECT_FALSE(tracker.translate(official(Referee::STOP, 10), &s).ball_in_play);
  EXPECT_TRUE(tracker.translate(official(Referee::FORCE_START, 11), &s).ball_in_play);
}

TEST(OfficialReferee, GameEventsOfAnyTypeKeepTeamRobotAndLocation) {
  GameEvent event;
  event.set_type(GameEvent::BOT_TIPPED_OVER);  // a type ubersim's own referee never gives
  auto* tipped = event.mutable_bot_tipped_over();
  tipped->set_by_team(::BLUE);
  tipped->set_by_bot(4);
  tipped->mutable_location()->set_x(-2.0F);
  tipped->mutable_location()->set_y(0.5F);
  const referee_event_t e = ssl::from_ssl_game_event(event, 7.0);
  EXPECT_EQ(e.type, static_cast<int32_t>(GameEvent::BOT_TIPPED_OVER));
  EXPECT_DOUBLE_EQ(e.sim_time, 7.0);
  ASSERT_TRUE(e.has_team);
  EXPECT_EQ(e.team, +team_t::BLUE);
  EXPECT_EQ(e.robot_id, 4);
  ASSERT_TRUE(e.has_location);
  EXPECT_DOUBLE_EQ(e.location[0], -2.0);
  EXPECT_EQ(e.description, "BOT_TIPPED_OVER");

  GameEvent goal;
  goal.set_type(GameEvent::GOAL);
  goal.mutable_goal()->set_by_team(::YELLOW);
  goal.mutable_goal()->set_kicking_bot(9);
  goal.mutable_goal()->set_message("a fine shot");
  const referee_event_t g = ssl::from_ssl_game_event(goal, 8.0);
  EXPECT_EQ(g.team, +team_t::YELLOW);
  EXPECT_EQ(g.robot_id, 9);
  EXPECT_FALSE(g.has_location);
  EXPECT_EQ(g.description, "GOAL: a fine shot");

  Referee in = official(Referee::STOP, 1);
  *in.add_game_events() = event;
  *in.add_game_events() = goal;
  ssl::OfficialRefereeTracker tracker;
  const referee_t out = tracker.translate(in, nullptr);
  ASSERT_EQ(out.num_events, 2);
  ASSERT_EQ(out.events.size(), 2U);
  EXPECT_EQ(out.events[1].robot_id, 9);
}

TEST(OfficialReferee, NothingNotANumberReachesTheTeams) {
  Referee in = official(Referee::BALL_PLACEMENT_YELLOW, 2);
  in.mutable_designated_position()->set_x(std::numeric_limits<float>::quiet_NaN());
  in.mutable_designated_position()->set_y(0);
  GameEvent event;
  event.set_type(GameEvent::BALL_LEFT_FIELD_TOUCH_LINE);
  event.mutable_ball_left_field_touch_line()->set_by_team(::YELLOW);
  event.mutable_ball_left_field_touch_line()->mutable_location()->set_x(
      std::numeric_limits<float>::infinity());
  event.mutable_ball_left_field_touch_line()->mutable_location()->set_y(0);
  *in.add_game_events() = event;
  ssl::OfficialRefereeTracker tracker;
  const referee_t out = tracker.translate(in, nullptr);
  EXPECT_FALSE(out.has_designated_position);
  EXPECT_TRUE(std::isfinite(out.designated_position[0]));
  ASSERT_EQ(out.events.size(), 1U);
  EXPECT_FALSE(out.events[0].has_location);
}
