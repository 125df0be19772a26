// REFEREE (referee_t) -> SSL Referee: every field the game controller's
// message has and the referee knows, in the protocol's units, and each game
// event with its payload; the bytes parse back as the same message.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <ubersim/team_t.hpp>

#include "ubersim/ssl_bridge/referee_translation.hpp"

using namespace ubersim;

namespace {

referee_t sample() {
  referee_t r{};
  r.sim_time = 40.0;
  r.stage = referee_t::STAGE_SECOND_HALF;
  r.stage_time_left = 12.25;
  r.command = referee_t::STOP;
  r.command_counter = 7;
  r.has_next_command = true;
  r.next_command = referee_t::DIRECT_FREE_BLUE;
  r.action_time_left = 0;
  r.blue_on_positive_half = true;
  r.yellow_score = 2;
  r.blue_score = 1;
  r.yellow_fouls = 3;
  r.blue_goalkeeper = 5;
  r.command_time = 38.5;
  r.yellow_name = "Yellow";
  r.blue_name = "TIGERs Mannheim";
  referee_event_t e{};
  e.sim_time = 39.25;
  e.type = referee_event_t::BALL_LEFT_FIELD_TOUCH_LINE;
  e.has_team = true;
  e.team = team_t::YELLOW;
  e.robot_id = 4;
  e.has_location = true;
  e.location[0] = 1.5;
  e.location[1] = -3.02;
  e.description = "ball over the touch line";
  r.events.push_back(e);
  r.num_events = 1;
  return r;
}

}  // namespace

TEST(RefereeTranslation, StateBecomesTheGameControllersMessage) {
  ssl::RefereeTranslator translator("ubersim-test");
  const Referee m = translator.translate(sample());
  EXPECT_EQ(m.source_identifier(), "ubersim-test");
  EXPECT_EQ(m.packet_timestamp(), 40'000'000u);  // sim time, like vision's t_capture
  EXPECT_EQ(m.stage(), Referee::NORMAL_SECOND_HALF);
  EXPECT_EQ(m.stage_time_left(), 12'250'000);
  EXPECT_EQ(m.command(), Referee::STOP);
  EXPECT_EQ(m.command_counter(), 7u);
  EXPECT_EQ(m.command_timestamp(), 38'500'000u);
  EXPECT_EQ(m.next_command(), Referee::DIRECT_FREE_BLUE);
  EXPECT_TRUE(m.blue_team_on_positive_half());
  EXPECT_EQ(m.yellow().score(), 2u);
  EXPECT_EQ(m.blue().score(), 1u);
  EXPECT_EQ(m.yellow().foul_counter(), 3u);
  EXPECT_EQ(m.blue().goalkeeper(), 5u);
  EXPECT_EQ(m.yellow().name(), "Yellow");  // an AI may find its colour by its name
  EXPECT_EQ(m.blue().name(), "TIGERs Mannheim");
  EXPECT_FALSE(m.has_designated_position());  // only with BALL_PLACEMENT_*
  EXPECT_FALSE(m.has_current_action_time_remaining());
  ASSERT_EQ(m.game_events_size(), 1);
  const GameEvent& g = m.game_events(0);
  EXPECT_EQ(g.type(), GameEvent::BALL_LEFT_FIELD_TOUCH_LINE);
  EXPECT_EQ(g.created_timestamp(), 39'250'000u);
  ASSERT_TRUE(g.has_ball_left_field_touch_line());
  EXPECT_EQ(g.ball_left_field_touch_line().by_team(), ::YELLOW);
  EXPECT_EQ(g.ball_left_field_touch_line().by_bot(), 4u);
  EXPECT_FLOAT_EQ(g.ball_left_field_touch_line().location().x(), 1.5f);  // m, as the protocol says
  EXPECT_EQ(m.status_message(), "ball over the touch line");
  ASSERT_TRUE(m.IsInitialized()) << m.InitializationErrorString();  // every required field

  std::string bytes;
  ASSERT_TRUE(m.SerializeToString(&bytes));
  Referee parsed;
  ASSERT_TRUE(parsed.ParseFromString(bytes));
  EXPECT_EQ(parsed.SerializeAsString(), bytes);
}

TEST(RefereeTranslation, EveryTimestampIsSimTimeInMicroseconds) {
  const ssl::RefereeTranslator translator("ubersim-test");
  auto r = sample();
  r.command = referee_t::DIRECT_FREE_BLUE;
  r.command_counter = 8;
  r.command_time = 41.0;
  r.sim_time = 42.000001;
  r.action_time_left = 9.5;
  const Referee m = translator.translate(r);
  EXPECT_EQ(m.packet_timestamp(), 42'000'001u);
  EXPECT_EQ(m.command_timestamp(), 41'000'000u);
  EXPECT_EQ(m.command(), Referee::DIRECT_FREE_BLUE);
  EXPECT_EQ(m.current_action_time_remaining(), 9'500'000);
  // What is no time (a hostile bus) is 0, never a wrapped or undefined number.
  for (const double bad : {-1.0, std::nan(""), 1e300, HUGE_VAL}) {
    r.sim_time = bad;
    r.command_time = bad;
    const Referee odd = translator.translate(r);
    EXPECT_EQ(odd.packet_timestamp(), 0u) << bad;
    EXPECT_EQ(odd.command_timestamp(), 0u) << bad;
  }
}

TEST(RefereeTranslation, EveryEventTypeCarriesItsPayload) {
  const std::pair<int32_t, std::function<bool(const GameEvent&)>> cases[] = {
      {referee_event_t::GOAL,
       [](const GameEvent& g) { return g.has_goal() && g.goal().by_team() == ::BLUE; }},
      {referee_event_t::BALL_LEFT_FIELD_GOAL_LINE,
       [](const GameEvent& g) { return g.has_ball_left_field_goal_line(); }},
      {referee_event_t::BOT_KICKED_BALL_TOO_FAST,
       [](const GameEvent& g) {
         return g.has_bot_kicked_ball_too_fast() &&
                g.bot_kicked_ball_too_fast().initial_ball_speed() == 7.0f;
       }},
      {referee_event_t::DEFENDER_IN_DEFENSE_AREA,
       [](const GameEvent& g) { return g.has_defender_in_defense_area(); }},
      {referee_event_t::ATTACKER_DOUBLE_TOUCHED_BALL,
       [](const GameEvent& g) {
         return g.has_attacker_double_touched_ball() &&
                g.attacker_double_touched_ball().by_bot() == 2;
       }},
      {referee_event_t::TOO_MANY_ROBOTS,
       [](const GameEvent& g) {
         return g.has_too_many_robots() && g.too_many_robots().num_robots_on_field() == 7;
       }},
      {referee_event_t::NO_PROGRESS_IN_GAME,
       [](const GameEvent& g) { return g.has_no_progress_in_game(); }},
  };
  for (const auto& [type, check] : cases) {
    referee_event_t e{};
    e.type = type;
    e.has_team = true;
    e.team = team_t::BLUE;
    e.robot_id = 2;
    e.value = 7.0;  // robots on the field, or the ball speed (m/s)
    const GameEvent g = ssl::to_ssl_game_event(e);
    EXPECT_EQ(static_cast<int>(g.type()), type);
    EXPECT_TRUE(check(g)) << type;
    EXPECT_TRUE(g.IsInitialized()) << type << ": " << g.InitializationErrorString();
  }
}
