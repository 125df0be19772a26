// The automatic referee's rules, one situation per test: ground truth is built
// by hand (robots, ball, its velocity), fed in sim-time order, and the
// decision (command, events, score, placement) is checked.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <ubersim/team_t.hpp>

#include "ubersim/config.hpp"
#include "ubersim/field_config.hpp"
#include "ubersim/referee/autoref.hpp"
#include "ubersim/referee/autoref_rules.hpp"
#include "ubersim/referee/referee_message.hpp"

using namespace ubersim;
using namespace ubersim::referee;

namespace {

constexpr double kDt = 0.01;  // s between the states fed in

field_geometry_t division_b() {
  return load_field_config(UBERSIM_SOURCE_CONFIG_DIR, "division_b").to_message(0.0215);
}

GameConfig shipped_config() {
  return load_game_config(UBERSIM_SOURCE_CONFIG_DIR, "division_b");
}

// A referee and the world it watches: 2 x 6 robots in their own halves (yellow
// defends negative x), the ball on the centre spot.
class Game {
 public:
  explicit Game(GameConfig config = shipped_config()) : referee_(config, division_b()) {
    state_.ball_present = true;
    for (int team = 0; team < 2; ++team) {
      for (int id = 0; id < 6; ++id) add_robot(team == 0 ? Team::Yellow : Team::Blue, id);
    }
  }

  void add_robot(Team team, int id) {
    robot_state_t r{};
    r.team = team == Team::Blue ? team_t::BLUE : team_t::YELLOW;
    r.robot_id = id;
    r.robot_type = "omni4_ssl";
    const double side = team == Team::Yellow ? -1 : 1;
    r.x = side * (1.0 + 0.5 * id);
    r.y = 1.5 - 0.6 * id;
    state_.robots.push_back(r);
    state_.num_robots = static_cast<int32_t>(state_.robots.size());
  }

  robot_state_t& robot(Team team, int id) {
    for (auto& r : state_.robots) {
      if (r.robot_id == id && (r.team == team_t::BLUE) == (team == Team::Blue)) return r;
    }
    throw std::runtime_error("no such robot");
  }

  void ball(double x, double y, double vx = 0, double vy = 0, double z = 0.0215) {
    state_.ball.position[0] = x;
    state_.ball.position[1] = y;
    state_.ball.position[2] = z;
    state_.ball.linear_velocity[0] = vx;
    state_.ball.linear_velocity[1] = vy;
    state_.ball.linear_velocity[2] = 0;
  }

  void set_field(const field_geometry_t& field) { referee_.set_field(field); }
  void team_heard(Team team) { referee_.team_heard(team); }

  // Feeds one state; collects what was decided.
  Decision tick() {
    state_.sim_time = time_;
    time_ += kDt;
    auto d = referee_.update(state_);
    for (const auto& e : d.events) events_.push_back(e);
    if (d.placement) placements_.push_back(*d.placement);
    return d;
  }
  // Feeds states for `seconds` (the world unchanged).
  void run(double seconds) {
    const int n = static_cast<int>(std::lround(seconds / kDt));
    for (int i = 0; i < n; ++i) tick();
  }
  // A placement arrives as physics would carry it out: the ball moves to the spot.
  void carry_out_placement() {
    ASSERT_TRUE(referee_.state().designated_position.has_value());
    ball(referee_.state().designated_position->first, referee_.state().designated_position->second);
  }
  // From the start of the game to the ball in play after the first kick-off.
  void kick_off_and_play() {
    run(referee_.config().stop_duration + kDt);
    carry_out_placement();
    run(referee_.config().prepare_duration + kDt);
    ASSERT_EQ(state().command, Command::NormalStart);
    ball(0.2, 0.0);  // the kick-off is taken
    tick();
    ASSERT_TRUE(state().ball_in_play);
    events_.clear();
    placements_.clear();
  }

  const RefereeState& state() const { return referee_.state(); }
  const std::vector<GameEvent>& events() const { return events_; }
  const std::vector<SituationRequest>& placements() const { return placements_; }
  double time() const { return time_; }

 private:
  AutoReferee referee_;
  sim_state_t state_{};
  double time_ = 0;
  std::vector<GameEvent> events_;
  std::vector<SituationRequest> placements_;
};

}  // namespace

TEST(AutoRefereeStart, StopThenKickOffPlacedThenNormalStartStartsTheFirstHalf) {
  Game game;
  game.tick();
  EXPECT_EQ(game.state().stage, Stage::FirstHalfPre);
  EXPECT_EQ(game.state().command, Command::Stop);
  ASSERT_TRUE(game.state().next_command.has_value());
  EXPECT_EQ(*game.state().next_command, Command::PrepareKickoffYellow);

  game.run(1.9);  // still inside the stop phase
  EXPECT_EQ(game.state().command, Command::Stop);
  EXPECT_TRUE(game.placements().empty());
  game.run(0.2);
  EXPECT_EQ(game.state().command, Command::PrepareKickoffYellow);
  ASSERT_EQ(game.placements().size(), 1u);
  EXPECT_EQ(game.placements()[0].kind, Situation::KickOff);
  EXPECT_EQ(game.placements()[0].team, Team::Yellow);

  game.run(1.1);
  EXPECT_EQ(game.state().command, Command::NormalStart);
  EXPECT_EQ(game.state().stage, Stage::FirstHalf);
  EXPECT_GT(game.state().stage_time_left, 299.8);  // the half's clock started at NORMAL_START
  EXPECT_LE(game.state().stage_time_left, 300.0);
  EXPECT_FALSE(game.state().ball_in_play);  // until the kick-off is taken
  game.ball(0.1, 0);
  game.tick();
  EXPECT_TRUE(game.state().ball_in_play);
}

// --team-wait: an SSL AI leaves its own halt only on STOP, so the game stays in HALT until every
// team on the field has sent a command.
TEST(AutoRefereeStart, HaltUntilEveryTeamOnTheFieldHasSentACommand) {
  GameConfig config = shipped_config();
  config.team_wait = 5;
  Game game(config);
  game.run(1.0);
  EXPECT_EQ(game.state().command, Command::Halt);
  EXPECT_EQ(game.state().stage, Stage::FirstHalfPre);
  game.team_heard(Team::Yellow);
  game.run(1.0);
  EXPECT_EQ(game.state().command, Command::Halt) << "blue has not been heard yet";
  game.team_heard(Team::Blue);
  game.tick();
  EXPECT_EQ(game.state().command, Command::Stop);
  ASSERT_TRUE(game.state().next_command.has_value());
  EXPECT_EQ(*game.state().next_command, Command::PrepareKickoffYellow);
}

TEST(AutoRefereeStart, ASilentTeamIsWaitedForOnlyTheTeamWait) {
  GameConfig config = shipped_config();
  config.team_wait = 2;
  Game game(config);
  game.team_heard(Team::Blue);
  game.run(1.9);
  EXPECT_EQ(game.state().command, Command::Halt);
  game.run(0.2);
  EXPECT_EQ(game.state().command, Command::Stop) << "yellow was waited for 2 s, no longer";
}

TEST(AutoRefereeGoal, WholeBallOverTheGoalLineBetweenThePostsScores) {
  Game game;
  game.kick_off_and_play();
  game.ball(4.5 + 0.02, 0.1);  // not wholly over the line yet
  game.tick();
  EXPECT_EQ(game.state().yellow.goals, 0);
  game.ball(4.5 + 0.03, 0.1, 2.0, 0.0);
  game.tick();
  ASSERT_EQ(game.events().size(), 1u);
  EXPECT_EQ(game.events()[0].type, EventType::Goal);
  EXPECT_EQ(*game.events()[0].team, Team::Yellow);  // yellow attacks the positive-x goal
  EXPECT_EQ(game.state().yellow.goals, 1);
  EXPECT_EQ(game.state().blue.goals, 0);
  EXPECT_EQ(game.state().command, Command::Stop);
  EXPECT_EQ(*game.state().next_command, Command::PrepareKickoffBlue);  // the other team kicks off

  // The ball still lies in the goal until the referee's placement arrives: no second goal.
  game.run(2.1);
  EXPECT_EQ(game.state().command, Command::PrepareKickoffBlue);
  game.run(0.5);
  EXPECT_EQ(game.state().yellow.goals, 1);
}

TEST(AutoRefereeGoal, OverTheCrossbarOrBesideThePostIsAGoalLineOutNotAGoal) {
  for (const auto& [y, z] : {std::pair{0.1, 0.3}, std::pair{0.7, 0.0215}}) {
    Game game;
    game.kick_off_and_play();
    game.ball(4.6, y, 2.0, 0.0, z);
    game.tick();
    ASSERT_EQ(game.events().size(), 1u);
    EXPECT_EQ(game.events()[0].type, EventType::BallLeftFieldGoalLine);
    EXPECT_EQ(game.state().yellow.goals, 0);
  }
}

TEST(AutoRefereeOut, TouchLineGivesTheOtherTeamAFreeKickOnTheLine) {
  Game game;
  game.kick_off_and_play();
  // Blue 2 touches the ball, which then rolls over the touch line at y = +3.
  auto& blue = game.robot(Team::Blue, 2);
  blue.x = 1.0;
  blue.y = 2.0;
  game.ball(1.0 + 0.09 + 0.0215 + 0.005, 2.0);
  game.tick();
  blue.y = 0;  // it drives away
  game.ball(1.5, 3.03, 0, 1.0);
  game.tick();
  ASSERT_EQ(game.events().size(), 1u);
  const auto& e = game.events()[0];
  EXPECT_EQ(e.type, EventType::BallLeftFieldTouchLine);
  EXPECT_EQ(*e.team, Team::Blue);
  EXPECT_EQ(e.robot, 2);
  EXPECT_EQ(game.state().command, Command::Stop);
  EXPECT_EQ(*game.state().next_command, Command::DirectFreeYellow);
  ASSERT_TRUE(game.state().designated_position);
  EXPECT_NEAR(game.state().designated_position->first, 1.5, 1e-9);
  EXPECT_NEAR(game.state().designated_position->second, 2.8, 1e-9);  // 0.2 m inside the line

  game.run(2.1);
  EXPECT_EQ(game.state().command, Command::DirectFreeYellow);
  ASSERT_EQ(game.placements().size(), 1u);
  EXPECT_EQ(game.placements()[0].kind, Situation::FreeKick);
  EXPECT_EQ(game.placements()[0].team, Team::Yellow);
  EXPECT_NEAR(game.placements()[0].y, 2.8, 1e-9);
  // The free kick is taken: play goes on.
  game.carry_out_placement();
  game.tick();
  EXPECT_FALSE(game.state().ball_in_play);
  game.ball(1.7, 2.7);
  game.tick();
  EXPECT_TRUE(game.state().ball_in_play);
}

TEST(AutoRefereeOut, GoalLineByTheAttackerIsAGoalKickByTheDefenderACorner) {
  {
    Game game;
    game.kick_off_and_play();
    auto& yellow = game.robot(Team::Yellow, 3);  // attacks +x
    yellow.x = 4.0;
    yellow.y = 1.5;
    game.ball(4.0 + 0.12, 1.5);
    game.tick();
    yellow.x = 3.0;
    game.ball(4.53, 1.5, 1.0, 0.0);
    game.tick();
    ASSERT_EQ(game.events().size(), 1u);
    EXPECT_EQ(game.events()[0].type, EventType::BallLeftFieldGoalLine);
    EXPECT_EQ(*game.state().next_command, Command::DirectFreeBlue);
    EXPECT_NEAR(game.state().designated_position->first, 3.5, 1e-9);
    EXPECT_NEAR(game.state().designated_position->second, 2.0, 1e-9);
  }
  {
    Game game;
    game.kick_off_and_play();
    auto& blue = game.robot(Team::Blue, 3);  // defends +x
    blue.x = 4.0;
    blue.y = -1.5;
    game.ball(4.0 + 0.12, -1.5);
    game.tick();
    blue.x = 3.0;
    game.ball(4.53, -1.5, 1.0, 0.0);
    game.tick();
    EXPECT_EQ(*game.state().next_command, Command::DirectFreeYellow);
    EXPECT_NEAR(game.state().designated_position->first, 4.3, 1e-9);  // the corner, 0.2 m in
    EXPECT_NEAR(game.state().designated_position->second, -2.8, 1e-9);
  }
}

TEST(AutoRefereeFouls, BallFasterThanTheLimitIsAFoulOfTheKickerAndPlayGoesOn) {
  Game game;
  game.kick_off_and_play();
  auto& yellow = game.robot(Team::Yellow, 1);
  yellow.x = 0.5;
  yellow.y = 0.0;
  game.ball(0.5 + 0.12, 0.0);
  game.tick();
  game.ball(0.8, 0.0, 6.0, 0.0);  // fast, but legal
  game.tick();
  EXPECT_TRUE(game.events().empty());
  game.ball(0.9, 0.0, 7.0, 1.0);
  game.tick();
  game.ball(1.0, 0.0, 7.0, 1.0);  // judged once per kick
  game.tick();
  ASSERT_EQ(game.events().size(), 1u);
  EXPECT_EQ(game.events()[0].type, EventType::BotKickedBallTooFast);
  EXPECT_EQ(*game.events()[0].team, Team::Yellow);
  EXPECT_EQ(game.events()[0].robot, 1);
  EXPECT_NEAR(game.events()[0].value, std::hypot(7.0, 1.0), 1e-9);
  EXPECT_EQ(game.state().yellow.fouls, 1);
  EXPECT_TRUE(game.state().ball_in_play);  // a non-stopping foul
}

TEST(AutoRefereeFouls, DefenderTouchingTheBallInItsDefenceAreaGivesAPenalty) {
  Game game;
  game.kick_off_and_play();
  // Blue defends +x; its defence area is x in [3.5, 4.5], |y| <= 1.
  auto& keeper = game.robot(Team::Blue, 0);
  keeper.x = 4.2;
  keeper.y = 0.0;
  game.ball(4.2 - 0.12, 0.0);  // the keeper may
  game.tick();
  EXPECT_TRUE(game.events().empty());
  auto& defender = game.robot(Team::Blue, 4);
  defender.x = 3.8;
  defender.y = 0.6;
  game.ball(3.8 - 0.12, 0.6);
  game.tick();
  ASSERT_EQ(game.events().size(), 1u);
  EXPECT_EQ(game.events()[0].type, EventType::DefenderInDefenseArea);
  EXPECT_EQ(*game.events()[0].team, Team::Blue);
  EXPECT_EQ(game.events()[0].robot, 4);
  EXPECT_EQ(game.state().blue.fouls, 1);
  EXPECT_EQ(*game.state().next_command, Command::PreparePenaltyYellow);
  // The official GC's mark: x = field_length / 2 - 6 m, negated for a team on the positive
  // half; yellow attacks +x from the negative half: 6 m from the blue goal.
  EXPECT_NEAR(game.state().designated_position->first, -1.5, 1e-9);
  game.run(2.1);
  ASSERT_EQ(game.placements().size(), 1u);
  EXPECT_EQ(game.placements()[0].kind, Situation::Penalty);
  EXPECT_EQ(game.placements()[0].team, Team::Yellow);
}

// A geometry applied at run time (SIM_GEOMETRY after a SET_FIELD) moves the penalty mark.
TEST(AutoRefereeFouls, PenaltyMarkFollowsAFieldChange) {
  Game game;
  game.kick_off_and_play();
  field_geometry_t changed = division_b();
  changed.penalty_mark_distance = 4.0;
  game.set_field(changed);
  auto& defender = game.robot(Team::Blue, 4);
  defender.x = 3.8;
  defender.y = 0.6;
  game.ball(3.8 - 0.12, 0.6);
  game.tick();
  ASSERT_EQ(game.events().size(), 1u);
  EXPECT_EQ(game.events()[0].type, EventType::DefenderInDefenseArea);
  EXPECT_NEAR(game.state().designated_position->first, 4.5 - 4.0, 1e-9);
}

TEST(AutoRefereeFouls, PartlyInsideTheDefenceAreaIsNoFoul) {
  Game game;
  game.kick_off_and_play();
  auto& defender = game.robot(Team::Blue, 4);
  defender.x = 3.55;  // hull reaches out of the area (needs x >= 3.59)
  defender.y = 0.0;
  game.ball(3.55 - 0.12, 0.0);
  game.tick();
  EXPECT_TRUE(game.events().empty());
}

TEST(AutoRefereeFouls, TooManyRobotsGivesTheOtherTeamAFreeKick) {
  Game game;
  game.kick_off_and_play();
  game.add_robot(Team::Yellow, 6);
  game.tick();
  ASSERT_EQ(game.events().size(), 1u);
  EXPECT_EQ(game.events()[0].type, EventType::TooManyRobots);
  EXPECT_EQ(*game.events()[0].team, Team::Yellow);
  EXPECT_EQ(game.events()[0].value, 7);
  EXPECT_EQ(game.state().yellow.fouls, 1);
  EXPECT_EQ(*game.state().next_command, Command::DirectFreeBlue);
}

namespace {

// Up to NORMAL_START of the first kick-off, then yellow 1 takes it: it stands
// at the ball, the ball rolls 0.1 m away (in play) and yellow 1 is clear of it.
void yellow_one_takes_the_kick_off(Game& game) {
  game.run(2.0 + kDt);  // the stop
  game.carry_out_placement();
  game.run(1.0 + kDt);  // prepare
  ASSERT_EQ(game.state().command, Command::NormalStart);
  auto& kicker = game.robot(Team::Yellow, 1);
  kicker.x = -0.12;
  kicker.y = 0.0;
  game.tick();  // touches the ball
  game.ball(0.1, 0.0);
  game.tick();  // the ball left its spot: in play
  ASSERT_TRUE(game.state().ball_in_play);
  ASSERT_TRUE(game.events().empty());
}

}  // namespace

TEST(AutoRefereeFouls, TheKickerTouchingTheBallAgainFirstIsADoubleTouchFreeKickForTheOthers) {
  Game game;
  yellow_one_takes_the_kick_off(game);
  auto& kicker = game.robot(Team::Yellow, 1);
  game.ball(0.3, 0.0);
  game.tick();
  EXPECT_TRUE(game.events().empty());
  kicker.x = 0.3 - 0.12;  // and touches it again, before anyone else
  game.tick();
  ASSERT_EQ(game.events().size(), 1u);
  EXPECT_EQ(game.events()[0].type, EventType::AttackerDoubleTouchedBall);
  EXPECT_EQ(static_cast<int>(game.events()[0].type), 14);  // the SSL number
  EXPECT_EQ(*game.events()[0].team, Team::Yellow);
  EXPECT_EQ(game.events()[0].robot, 1);
  EXPECT_TRUE(game.events()[0].foul);
  EXPECT_EQ(game.state().yellow.fouls, 1);
  EXPECT_EQ(game.state().command, Command::Stop);
  EXPECT_EQ(*game.state().next_command, Command::DirectFreeBlue);
  ASSERT_TRUE(game.state().designated_position.has_value());
  EXPECT_NEAR(game.state().designated_position->first, 0.3, 1e-9);
}

TEST(AutoRefereeFouls, NoDoubleTouchOnceAnotherRobotTouchedTheBall) {
  Game game;
  yellow_one_takes_the_kick_off(game);
  auto& kicker = game.robot(Team::Yellow, 1);
  auto& other = game.robot(Team::Blue, 2);
  other.x = 0.1 + 0.12;  // a blue robot touches it first
  other.y = 0.0;
  game.tick();
  other.x = 2.0;
  game.ball(0.3, 0.0);
  game.tick();
  kicker.x = 0.3 - 0.12;  // then the kicker again: legal
  game.tick();
  EXPECT_TRUE(game.events().empty());
  EXPECT_TRUE(game.state().ball_in_play);
  EXPECT_EQ(game.state().command, Command::NormalStart);
}

TEST(AutoRefereeProgress, BallStillForTenSecondsIsNoProgressThenForceStart) {
  Game game;
  game.kick_off_and_play();
  game.ball(2.0, 2.98);  // stuck at the wall side of the touch line
  game.run(9.9);
  EXPECT_TRUE(game.events().empty());
  game.run(0.2);
  ASSERT_EQ(game.events().size(), 1u);
  EXPECT_EQ(game.events()[0].type, EventType::NoProgressInGame);
  EXPECT_FALSE(game.events()[0].foul);
  EXPECT_EQ(game.state().command, Command::Stop);
  EXPECT_EQ(*game.state().next_command, Command::ForceStart);
  game.run(2.1);
  EXPECT_EQ(game.state().command, Command::ForceStart);
  ASSERT_EQ(game.placements().size(), 1u);
  EXPECT_EQ(game.placements()[0].kind, Situation::BallPlacement);
  EXPECT_NEAR(game.placements()[0].y, 2.8, 1e-9);  // moved off the line
  EXPECT_TRUE(game.state().ball_in_play);
}

TEST(AutoRefereeProgress, AFreeKickNotTakenInTimeBecomesAForceStart) {
  Game game;
  game.kick_off_and_play();
  game.ball(1.0, 3.05);
  game.tick();
  game.run(2.1);
  // Nobody touched it since the kick-off: the team whose half it left in is
  // taken to have put it out.
  ASSERT_EQ(game.state().command, Command::DirectFreeYellow);
  game.carry_out_placement();
  game.run(9.8);
  EXPECT_EQ(game.state().command, Command::DirectFreeYellow);
  EXPECT_FALSE(game.state().ball_in_play);
  game.run(0.3);
  EXPECT_EQ(game.state().command, Command::ForceStart);
  EXPECT_TRUE(game.state().ball_in_play);
}

TEST(AutoRefereeTime, HalvesAndGameLengthEndTheGame) {
  GameConfig config = shipped_config();
  config.game_length = 20;
  config.half_time_break = 1;
  Game game(config);
  game.kick_off_and_play();
  game.run(5);
  game.ball(0.5, 0.5);  // keep the game progressing
  game.run(4.5);
  EXPECT_EQ(game.state().stage, Stage::FirstHalf);
  game.run(0.6);
  EXPECT_EQ(game.state().stage, Stage::HalfTime);
  EXPECT_EQ(game.state().command, Command::Halt);
  game.run(1.1);
  EXPECT_EQ(game.state().stage, Stage::SecondHalfPre);
  EXPECT_EQ(*game.state().next_command, Command::PrepareKickoffBlue);
  game.run(2.1);
  game.carry_out_placement();
  game.run(1.1);
  EXPECT_EQ(game.state().stage, Stage::SecondHalf);
  EXPECT_GT(game.state().stage_time_left, 9.5);
  game.ball(0.0, 0.2);
  game.run(5);
  game.ball(0.5, 0.2);
  game.run(game.state().stage_time_left - 0.1);
  EXPECT_FALSE(game.state().game_over);
  game.run(0.2);
  EXPECT_EQ(game.state().stage, Stage::PostGame);
  EXPECT_EQ(game.state().command, Command::Halt);
  EXPECT_TRUE(game.state().game_over);
  const int counter = game.state().command_counter;
  game.run(1);  // nothing happens after the end
  EXPECT_EQ(game.state().command_counter, counter);
}

TEST(AutoRefereeStats, AKickIntoTheGoalMouthIsAShotAndTouchesGivePossession) {
  Game game;
  game.kick_off_and_play();
  auto& yellow = game.robot(Team::Yellow, 1);
  yellow.x = 2.0;
  yellow.y = 0.0;
  game.ball(2.12, 0.0);
  game.run(1.0);                  // yellow has the ball for 1 s
  game.ball(2.3, 0.0, 3.0, 0.2);  // kicked towards the goal
  game.tick();
  game.ball(2.4, 0.0, 3.0, 0.2);
  game.tick();
  EXPECT_EQ(game.state().yellow.shots, 1);
  EXPECT_EQ(game.state().blue.shots, 0);
  EXPECT_NEAR(game.state().yellow.possession, 1.02, 0.03);
  EXPECT_NEAR(game.state().blue.possession, 0.0, 1e-9);
}

TEST(AutoRefereeRules, GeometryOfGoalsOutsAndFreeKickSpots) {
  const auto field = division_b();
  EXPECT_EQ(goal_side(field, -4.53, 0.0, 0.02), -1);
  EXPECT_EQ(goal_side(field, -4.51, 0.0, 0.02), 0);
  EXPECT_EQ(ball_out(field, 0, -3.03), BallOut::TouchLine);
  EXPECT_EQ(ball_out(field, 0, -3.01), BallOut::No);
  double x = 4.4, y = 0.3;  // inside the defence area
  free_kick_spot(field, x, y);
  EXPECT_NEAR(x, 3.3, 1e-9);
  EXPECT_NEAR(y, 0.3, 1e-9);
  EXPECT_TRUE(heads_into_goal(field, 1, 2.0, 0.0, 3.0, 0.3));
  EXPECT_FALSE(heads_into_goal(field, 1, 2.0, 0.0, 3.0, 2.0));
  EXPECT_FALSE(heads_into_goal(field, 1, 2.0, 0.0, -3.0, 0.0));
}

namespace {

// A game config with every key (one a line, in this order), `replace` put in
// place of the line that starts with its key, `extra` appended.
std::string game_config_text(const std::string& replace = "", const std::string& extra = "") {
  std::string text;
  for (const char* line :
       {"GAME_LENGTH = 30", "HALVES = 2", "HALF_TIME_BREAK = 1", "STOP_DURATION = 2",
        "PREPARE_DURATION = 1", "RESTART_TIMEOUT = 10", "NO_PROGRESS_TIME = 10",
        "PROGRESS_DISTANCE = 0.1", "MAX_ROBOTS = 6", "MAX_BALL_SPEED = 6.5", "ROBOT_RADIUS = 0.09",
        "TOUCH_MARGIN = 0.015", "KEEPER_YELLOW = 0", "KEEPER_BLUE = 0", "FIRST_KICKOFF = yellow"}) {
    const std::string key = std::string(line).substr(0, std::string(line).find(' '));
    const bool replaced = !replace.empty() && replace.rfind(key + " ", 0) == 0;
    text += (replaced ? replace : std::string(line)) + "\n";
  }
  return text + extra;
}

// The message of the ConfigError that reading `text` as game.cfg throws.
std::string game_config_error(const std::string& text) {
  try {
    load_game_config(ConfigFile::parse(text, "game.cfg"));
  } catch (const ConfigError& error) {
    return error.what();
  }
  return "(no error)";
}

}  // namespace

TEST(AutoRefereeConfig, TheTestTextIsAValidConfig) {
  EXPECT_EQ(load_game_config(ConfigFile::parse(game_config_text("KEEPER_BLUE = 99"), "game.cfg"))
                .keeper_blue,
            99);
}

TEST(AutoRefereeConfig, UnknownKeyIsAnErrorNamingFileAndLine) {
  const std::string error = game_config_error(game_config_text("", "GAME_LENGHT = 20\n"));
  EXPECT_NE(error.find("game.cfg:16"), std::string::npos) << error;
}

TEST(AutoRefereeConfig, IntegerOutOfRangeNamesFileLineAndRange) {
  struct Case {
    std::string line;
    std::string where;
    std::string range;
  };
  for (const Case& c :
       {Case{"HALVES = 3", "game.cfg:2", "[1, 2]"}, Case{"MAX_ROBOTS = 0", "game.cfg:9", "[1, 16]"},
        Case{"MAX_ROBOTS = 17", "game.cfg:9", "[1, 16]"},
        Case{"KEEPER_YELLOW = -1", "game.cfg:13", "[0, 99]"},
        // Once cast to int unchecked: keeper 0.
        Case{"KEEPER_BLUE = 4294967296", "game.cfg:14", "[0, 99]"}}) {
    const std::string error = game_config_error(game_config_text(c.line));
    const std::string key = c.line.substr(0, c.line.find(' '));
    const std::string value = c.line.substr(c.line.rfind(' ') + 1);
    for (const std::string& piece : {c.where, key, "expected an integer in " + c.range, value}) {
      EXPECT_NE(error.find(piece), std::string::npos)
          << "'" << error << "' lacks '" << piece << "'";
    }
  }
  const std::string error = game_config_error(game_config_text("HALVES = 1.5"));
  EXPECT_NE(error.find("game.cfg:2"), std::string::npos) << error;
  EXPECT_NE(error.find("HALVES"), std::string::npos) << error;
}

TEST(AutoRefereeConfig, TeamNamesComeFromTheConfigWithYellowAndBlueWhenLeftOut) {
  const GameConfig shipped = shipped_config();
  EXPECT_EQ(shipped.yellow_name, "Yellow");
  EXPECT_EQ(shipped.blue_name, "Blue");
  const GameConfig left_out = load_game_config(ConfigFile::parse(game_config_text(), "game.cfg"));
  EXPECT_EQ(left_out.yellow_name, "Yellow");
  EXPECT_EQ(left_out.blue_name, "Blue");
  const GameConfig named = load_game_config(ConfigFile::parse(
      game_config_text("", "YELLOW_NAME = \"TIGERs Mannheim\"\nBLUE_NAME = ER-Force\n"),
      "game.cfg"));
  EXPECT_EQ(named.yellow_name, "TIGERs Mannheim");
  EXPECT_EQ(named.blue_name, "ER-Force");
  const auto m = to_message(RefereeState{}, named, FieldSides{}, 0.0);
  EXPECT_EQ(m.yellow_name, "TIGERs Mannheim");
  EXPECT_EQ(m.blue_name, "ER-Force");
}

TEST(AutoRefereeConfig, AnEmptyOrOverlongTeamNameIsAnErrorNamingFileAndLine) {
  for (const std::string& line :
       {std::string("YELLOW_NAME = \"\""), "BLUE_NAME = " + std::string(65, 'x'),
        std::string("BLUE_NAME =")}) {
    const std::string error = game_config_error(game_config_text("", line + "\n"));
    EXPECT_NE(error.find("game.cfg:16"), std::string::npos) << line << ": " << error;
  }
  EXPECT_EQ(team_name_problem("Yellow"), "");
  EXPECT_NE(team_name_problem("tab\there"), "");
}

TEST(AutoRefereeMessage, StateGoesOnTheWireWithSslNumberingAndIntoTheLog) {
  Game game;
  game.kick_off_and_play();
  game.ball(4.53, 0.0, 2.0, 0.0);
  game.tick();
  GameConfig config = shipped_config();
  config.keeper_blue = 3;
  const auto m = to_message(game.state(), config, FieldSides{}, 12.5);
  EXPECT_EQ(m.sim_time, 12.5);
  EXPECT_EQ(m.command, int{referee_t::STOP});
  EXPECT_EQ(m.command, 1);  // Referee.Command.STOP
  EXPECT_EQ(m.stage, int{referee_t::STAGE_FIRST_HALF});
  EXPECT_TRUE(m.has_next_command);
  EXPECT_EQ(m.next_command, int{referee_t::PREPARE_KICKOFF_BLUE});
  EXPECT_EQ(m.yellow_score, 1);
  EXPECT_EQ(m.blue_goalkeeper, 3);
  EXPECT_TRUE(m.blue_on_positive_half);
  EXPECT_TRUE(m.has_designated_position);
  ASSERT_EQ(m.num_events, 1);
  ASSERT_EQ(m.events.size(), 1u);
  EXPECT_EQ(m.events[0].type, int{referee_event_t::GOAL});
  EXPECT_EQ(m.events[0].type, 8);  // GameEvent.Type.GOAL
  EXPECT_EQ(m.events[0].team, int{team_t::YELLOW});

  const std::string line = event_line(game.state().events[0]);
  EXPECT_NE(line.find("\"event\": \"GOAL\""), std::string::npos) << line;
  EXPECT_NE(line.find("\"team\": \"yellow\""), std::string::npos) << line;
  GameEvent quoted;
  quoted.description = "a \"quoted\"\nline";
  EXPECT_NE(event_line(quoted).find(R"(a \"quoted\"\u000aline)"), std::string::npos)
      << event_line(quoted);
}

// A sync run in which the radio emulator dropped a client (SIM_SYNC_STATUS):
// the result says which team was without control, and for how long of the game.
TEST(ResultLine, SaysWhichTeamPlayedWithoutControl) {
  ubersim::sync_status_t status{};
  status.client[0] = "demo_yellow";
  status.drops[0] = 2;
  status.without_control[0] = 1.5;  // a first drop that ended
  status.dropped_at[0] = 8.0;       // a second, still going
  status.dropped_at[1] = -1;
  const auto losses = ubersim::referee::control_losses(status, 10.0);
  ASSERT_EQ(losses.size(), 1u);
  EXPECT_EQ(losses[0].team, "yellow");
  EXPECT_DOUBLE_EQ(losses[0].without_control, 3.5);
  EXPECT_EQ(ubersim::referee::degraded_text(losses),
            "DEGRADED: yellow without control for 3.5000 s of sim time (sync client "
            "'demo_yellow' dropped 2 times)");
  const ubersim::referee::RefereeState state;
  const std::string line = ubersim::referee::result_line(state, 10.0, 1.0, losses);
  EXPECT_NE(line.find(R"("degraded": [{"team": "yellow", "client": "demo_yellow", "drops": 2, )"
                      R"("without_control": 3.5000}], "wall_time")"),
            std::string::npos)
      << line;
  EXPECT_EQ(ubersim::referee::result_line(state, 10.0, 1.0).find("degraded"), std::string::npos);
  // A drop after the game's end took nothing from it.
  EXPECT_TRUE(ubersim::referee::control_losses(status, 7.0).size() == 1u);
  status.without_control[0] = 0;
  EXPECT_TRUE(ubersim::referee::control_losses(status, 7.0).empty());
}
