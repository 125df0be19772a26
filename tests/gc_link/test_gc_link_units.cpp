// The pieces of the CI-port link against the official definitions (the
// generated classes of the GC's own .proto files): framing, the conversation
// that settles a tick, the CiInput contents, the operator and the field keeper.
#include <google/protobuf/io/zero_copy_stream_impl_lite.h>
#include <google/protobuf/util/delimited_message_util.h>
#include <gtest/gtest.h>

#include <cmath>
#include <ubersim/team_t.hpp>

#include "ubersim/field_config.hpp"
#include "ubersim/gc_link/ci_conversation.hpp"
#include "ubersim/gc_link/ci_framing.hpp"
#include "ubersim/gc_link/field_keeper.hpp"
#include "ubersim/gc_link/gc_inputs.hpp"
#include "ubersim/gc_link/gc_link.hpp"

namespace {

using namespace ubersim;
using namespace ubersim::gc_link;

CiOutput output_with(Referee::Command command, const std::string& status = "") {
  CiOutput out;
  out.mutable_referee_msg()->set_command(command);
  if (!status.empty()) out.mutable_referee_msg()->set_status_message(status);
  return out;
}

std::string official_delimited(const google::protobuf::MessageLite& message) {
  std::string bytes;
  google::protobuf::io::StringOutputStream stream(&bytes);
  EXPECT_TRUE(google::protobuf::util::SerializeDelimitedToZeroCopyStream(message, &stream));
  return bytes;
}

CiInput big_input() {
  CiInput input;
  input.set_timestamp(123456789);
  for (int i = 0; i < 40; ++i) {
    input.add_api_inputs()->mutable_change()->set_origin("a fairly long origin " +
                                                         std::to_string(i));
  }
  return input;
}

TEST(CiFraming, IsProtobufsSizeDelimitedForm) {
  CiInput small;
  small.set_timestamp(5);
  EXPECT_EQ(frame(small), official_delimited(small));
  const CiInput big = big_input();  // over 127 bytes: a two-byte size
  ASSERT_GT(big.ByteSizeLong(), 127u);
  EXPECT_EQ(frame(big), official_delimited(big));
}

TEST(CiFraming, ReaderCutsAStreamFedByteByByteIntoItsMessages) {
  CiInput small;
  small.set_timestamp(5);
  const std::string stream = frame(small) + frame(big_input()) + frame(CiInput());
  FrameReader reader;
  std::vector<std::string> messages;
  for (char c : stream) {
    reader.feed(std::string_view(&c, 1));
    while (auto m = reader.next()) messages.push_back(*m);
  }
  ASSERT_EQ(messages.size(), 3u);
  EXPECT_EQ(messages[0], small.SerializeAsString());
  EXPECT_EQ(messages[1], big_input().SerializeAsString());
  EXPECT_EQ(messages[2], "");  // an empty message is a size of 0
  EXPECT_EQ(reader.buffered(), 0u);
}

TEST(CiFraming, ReaderRefusesSizesItCannotTrust) {
  FrameReader too_long;
  too_long.feed(std::string(11, '\xff'));
  EXPECT_THROW(too_long.next(), FramingError);
  FrameReader too_big;
  too_big.feed("\x80\x80\x80\x80\x01");  // 2^28 bytes
  EXPECT_THROW(too_big.next(), FramingError);
  FrameReader partial;
  partial.feed(
      "\x05"
      "abc");
  EXPECT_FALSE(partial.next().has_value());  // waits for the rest
}

TEST(CiConversation, SettlesATickWithTwoBarriersThenSendsTheChanges) {
  std::uint64_t barriers = 0;
  CiInput tick;
  tick.set_timestamp(42);
  std::vector<Input> changes(1);
  changes[0].set_reset_match(true);
  CiConversation talk(tick, changes, barriers);
  auto first = talk.next_input();
  ASSERT_TRUE(first);
  EXPECT_EQ(first->timestamp(), 42);
  EXPECT_EQ(first->api_inputs_size(), 0);  // the tick alone
  EXPECT_FALSE(talk.next_input());         // waits for its answer
  talk.on_output(output_with(Referee::STOP));
  for (int barrier = 1; barrier <= 3; ++barrier) {
    auto input = talk.next_input();
    ASSERT_TRUE(input) << barrier;
    EXPECT_FALSE(input->has_timestamp());
    const Input& last = input->api_inputs(input->api_inputs_size() - 1);
    EXPECT_EQ(last.change().set_status_message_change().status_message(),
              barrier_text(static_cast<std::uint64_t>(barrier)));
    EXPECT_EQ(input->api_inputs_size(), barrier == 3 ? 2 : 1);  // the changes go with the third
    // Outputs of work queued before the barrier do not end the wait.
    talk.on_output(output_with(Referee::NORMAL_START));
    EXPECT_FALSE(talk.next_input());
    talk.on_output(output_with(Referee::FORCE_START, barrier_text(barrier)));
  }
  EXPECT_TRUE(talk.done());
  EXPECT_EQ(talk.referee().command(), Referee::FORCE_START);
  EXPECT_EQ(barriers, 3u);
}

TEST(CiConversation, WithoutChangesTwoBarriersSuffice) {
  std::uint64_t barriers = 10;
  CiConversation talk(CiInput(), {}, barriers);
  talk.next_input();
  talk.on_output(output_with(Referee::STOP));
  talk.next_input();
  talk.on_output(output_with(Referee::STOP, barrier_text(11)));
  talk.next_input();
  talk.on_output(output_with(Referee::STOP, barrier_text(12)));
  EXPECT_TRUE(talk.done());
  EXPECT_FALSE(talk.next_input());
}

TEST(GcInputs, SetupMakesAFreshFriendlyMatchWithOurTeamsAndNoBallPlacingTeam) {
  GameSetup setup;
  setup.yellow_name = "Ours";
  setup.blue_keeper = 3;
  setup.first_kickoff = ubersim::Team::Blue;
  const auto inputs = setup_inputs(setup);
  ASSERT_EQ(inputs.size(), 5u);
  EXPECT_TRUE(inputs[0].reset_match());
  const Config& config = inputs[1].config_delta();
  EXPECT_TRUE(config.auto_continue());
  const auto& ours = config.auto_ref_configs().at(kAutoRefName).game_event_behavior();
  EXPECT_EQ(ours.at("POSSIBLE_GOAL"), AutoRefConfig::BEHAVIOR_ACCEPT);
  EXPECT_EQ(ours.at("BOT_KICKED_BALL_TOO_FAST"), AutoRefConfig::BEHAVIOR_ACCEPT);
  const auto& game = inputs[2].change().update_config_change();
  EXPECT_EQ(game.division(), DIV_B);
  EXPECT_EQ(game.first_kickoff_team(), BLUE);
  EXPECT_EQ(game.match_type(), FRIENDLY);
  const auto& yellow = inputs[3].change().update_team_state_change();
  EXPECT_EQ(yellow.for_team(), YELLOW);
  EXPECT_EQ(yellow.team_name().value(), "Ours");
  EXPECT_FALSE(yellow.can_place_ball().value());
  EXPECT_FALSE(yellow.on_positive_half().value());  // yellow defends negative x
  const auto& blue = inputs[4].change().update_team_state_change();
  EXPECT_EQ(blue.goalkeeper().value(), 3);
  EXPECT_TRUE(blue.on_positive_half().value());
}

TEST(GcInputs, GoalsAreReportedAsPossibleGoalsAndFoulsWithTheirRobot) {
  referee::GameEvent goal;
  goal.type = referee::EventType::Goal;
  goal.team = ubersim::Team::Blue;
  goal.robot = 4;
  goal.has_location = true;
  goal.x = -4.5;
  goal.y = 0.25;
  const auto input = report(goal);
  ASSERT_TRUE(input);
  const GameEvent& event = input->change().add_game_event_change().game_event();
  EXPECT_EQ(event.type(), GameEvent::POSSIBLE_GOAL);
  EXPECT_EQ(event.origin(0), kAutoRefName);
  EXPECT_EQ(event.possible_goal().by_team(), BLUE);
  EXPECT_EQ(event.possible_goal().kicking_bot(), 4u);
  EXPECT_FLOAT_EQ(event.possible_goal().location().x(), -4.5f);  // m, as the GC's events are

  referee::GameEvent fast;
  fast.type = referee::EventType::BotKickedBallTooFast;
  fast.team = ubersim::Team::Yellow;
  fast.robot = 2;
  fast.value = 7.5;
  const auto foul = report(fast)->change().add_game_event_change().game_event();
  EXPECT_EQ(foul.bot_kicked_ball_too_fast().by_team(), YELLOW);
  EXPECT_EQ(foul.bot_kicked_ball_too_fast().by_bot(), 2u);
  EXPECT_FLOAT_EQ(foul.bot_kicked_ball_too_fast().initial_ball_speed(), 7.5f);

  referee::GameEvent stall;
  stall.type = referee::EventType::NoProgressInGame;
  EXPECT_FALSE(report(stall));  // the GC judges progress itself
}

TEST(GcInputs, ReportsOnlyWhileTheBallIsInPlayOrARestartIsTaken) {
  Referee gc;
  for (auto [command, wanted] : {std::pair{Referee::NORMAL_START, true},
                                 {Referee::DIRECT_FREE_BLUE, true},
                                 {Referee::FORCE_START, true},
                                 {Referee::STOP, false},
                                 {Referee::HALT, false},
                                 {Referee::PREPARE_KICKOFF_YELLOW, false}}) {
    gc.set_command(command);
    EXPECT_EQ(reports_wanted(gc), wanted) << Referee::Command_Name(command);
  }
}

TEST(GcInputs, GeometryIsTheFieldInMillimetres) {
  const auto field = load_field_config(UBERSIM_SOURCE_CONFIG_DIR, "division_b").to_message(0.0215);
  const SSL_GeometryData data = geometry_data(field);
  EXPECT_EQ(data.field().field_length(), 9000);
  EXPECT_EQ(data.field().field_width(), 6000);
  EXPECT_EQ(data.field().penalty_area_depth(), std::lround(field.penalty_area_depth * 1000));
  EXPECT_EQ(data.field().goal_center_to_penalty_mark(),
            std::lround(field.penalty_mark_distance * 1000));
  EXPECT_TRUE(data.IsInitialized());  // every required field of the official message
}

Referee at_stage(Referee::Stage stage, Referee::Command command, std::int64_t left_us,
                 std::uint32_t counter = 1) {
  Referee gc;
  gc.set_stage(stage);
  gc.set_command(command);
  gc.set_stage_time_left(left_us);
  gc.set_command_counter(counter);
  return gc;
}

TEST(Operator, StartsTheMatchResumesAfterAHeldHaltAndEndsHalvesAndTheBreak) {
  Operator op;
  auto first = op.decide(Referee(), 0);
  ASSERT_EQ(first.size(), 1u);
  EXPECT_EQ(first[0].change().new_command_change().command().type(), Command::STOP);
  const Referee halted = at_stage(Referee::NORMAL_FIRST_HALF, Referee::HALT, 10'000'000, 7);
  EXPECT_TRUE(op.decide(halted, 3.0).empty());
  EXPECT_TRUE(op.decide(halted, 3.0 + Operator::kHaltHold - 0.01).empty());
  auto resume = op.decide(halted, 3.0 + Operator::kHaltHold);
  ASSERT_EQ(resume.size(), 1u);
  EXPECT_EQ(resume[0].change().new_command_change().command().type(), Command::STOP);
  EXPECT_TRUE(op.decide(at_stage(Referee::NORMAL_FIRST_HALF, Referee::NORMAL_START, 1), 5).empty());
  const auto half = op.decide(at_stage(Referee::NORMAL_FIRST_HALF, Referee::NORMAL_START, 0), 6);
  ASSERT_EQ(half.size(), 1u);
  EXPECT_EQ(half[0].change().change_stage_change().new_stage(), Referee::NORMAL_HALF_TIME);
  EXPECT_TRUE(op.decide(at_stage(Referee::NORMAL_HALF_TIME, Referee::HALT, 1, 9), 7).empty());
  EXPECT_TRUE(op.decide(at_stage(Referee::NORMAL_HALF_TIME, Referee::HALT, 1, 9), 9).empty());
  const auto second = op.decide(at_stage(Referee::NORMAL_HALF_TIME, Referee::HALT, -1, 9), 10);
  EXPECT_EQ(second.at(0).change().change_stage_change().new_stage(),
            Referee::NORMAL_SECOND_HALF_PRE);
  const auto end = op.decide(at_stage(Referee::NORMAL_SECOND_HALF, Referee::STOP, -5), 20);
  EXPECT_EQ(end.at(0).change().change_stage_change().new_stage(), Referee::POST_GAME);
  EXPECT_TRUE(op.decide(at_stage(Referee::POST_GAME, Referee::HALT, 0, 12), 30).empty());
}

sim_state_t ball_at(double t, double x, double y) {
  sim_state_t s{};
  s.sim_time = t;
  s.dt = 1.0 / 240;
  s.ball_present = true;
  s.ball.position[0] = x;
  s.ball.position[1] = y;
  return s;
}

TEST(FieldKeeper, PlacesTheBallAtTheDesignatedPositionOnceTheStopIsHeld) {
  FieldKeeper keeper;
  Referee gc = at_stage(Referee::NORMAL_FIRST_HALF, Referee::STOP, 1, 3);
  gc.mutable_designated_position()->set_x(1000);
  gc.mutable_designated_position()->set_y(-500);
  EXPECT_FALSE(keeper.decide(gc, ball_at(10, 3, 2)));
  EXPECT_FALSE(keeper.decide(gc, ball_at(10 + FieldKeeper::kHold - 0.01, 3, 2)));
  const auto placed = keeper.decide(gc, ball_at(10 + FieldKeeper::kHold, 3, 2));
  ASSERT_TRUE(placed);
  EXPECT_EQ(placed->kind, referee::Situation::BallPlacement);
  EXPECT_DOUBLE_EQ(placed->x, 1.0);
  EXPECT_DOUBLE_EQ(placed->y, -0.5);
  EXPECT_FALSE(keeper.decide(gc, ball_at(10.6, 3, 2)));        // not again at once
  EXPECT_FALSE(keeper.decide(gc, ball_at(11.2, 1.05, -0.5)));  // there (within 0.1 m)
  gc.set_command(Referee::NORMAL_START);
  gc.set_command_counter(4);
  EXPECT_FALSE(keeper.decide(gc, ball_at(12, 3, 2)));  // in play: the teams' business
}

TEST(FieldKeeper, SetsUpKickoffsAndPenaltiesOncePerCommand) {
  FieldKeeper keeper;
  Referee gc = at_stage(Referee::NORMAL_FIRST_HALF, Referee::PREPARE_KICKOFF_BLUE, 1, 5);
  const auto kickoff = keeper.decide(gc, ball_at(1, 2, 2));
  ASSERT_TRUE(kickoff);
  EXPECT_EQ(kickoff->kind, referee::Situation::KickOff);
  EXPECT_EQ(kickoff->team, ubersim::Team::Blue);
  EXPECT_FALSE(keeper.decide(gc, ball_at(2, 2, 2)));
  gc.set_command(Referee::PREPARE_PENALTY_YELLOW);
  gc.set_command_counter(6);
  const auto penalty = keeper.decide(gc, ball_at(3, 2, 2));
  ASSERT_TRUE(penalty);
  EXPECT_EQ(penalty->kind, referee::Situation::Penalty);
  EXPECT_EQ(penalty->team, ubersim::Team::Yellow);
}

}  // namespace
