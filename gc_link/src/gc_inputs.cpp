#include "ubersim/gc_link/gc_inputs.hpp"

#include <cmath>

namespace ubersim::gc_link {
namespace {

using referee::EventType;

::Team ssl_team(ubersim::Team team) {
  return team == ubersim::Team::Yellow ? YELLOW : BLUE;
}

std::int32_t mm(double metres) {
  return static_cast<std::int32_t>(std::lround(metres * 1000));
}

void set_location(Vector2& out, const referee::GameEvent& event) {
  out.set_x(static_cast<float>(event.x));
  out.set_y(static_cast<float>(event.y));
}

Input team_state(::Team team, const std::string& name, int keeper, bool positive_half) {
  Input input;
  auto* change = input.mutable_change();
  change->set_origin(kAutoRefName);
  auto* update = change->mutable_update_team_state_change();
  update->set_for_team(team);
  update->mutable_team_name()->set_value(name);
  update->mutable_goalkeeper()->set_value(keeper);
  update->mutable_on_positive_half()->set_value(positive_half);
  update->mutable_can_place_ball()->set_value(false);
  return input;
}

// The payload of a BallLeftField-like event: team, robot, location.
template <class Payload>
void fill_foul(Payload& p, const referee::GameEvent& e) {
  if (e.team) p.set_by_team(ssl_team(*e.team));
  if (e.robot >= 0) p.set_by_bot(static_cast<std::uint32_t>(e.robot));
  if (e.has_location) set_location(*p.mutable_location(), e);
}

// The event types ubersim reports; its autoref config accepts each of them.
const std::vector<GameEvent::Type>& reported_types() {
  static const std::vector<GameEvent::Type> types = {
      GameEvent::POSSIBLE_GOAL,
      GameEvent::BALL_LEFT_FIELD_TOUCH_LINE,
      GameEvent::BALL_LEFT_FIELD_GOAL_LINE,
      GameEvent::ATTACKER_DOUBLE_TOUCHED_BALL,
      GameEvent::BOT_KICKED_BALL_TOO_FAST,
      GameEvent::DEFENDER_IN_DEFENSE_AREA,
  };
  return types;
}

}  // namespace

std::vector<Input> setup_inputs(const GameSetup& setup) {
  std::vector<Input> inputs;
  inputs.emplace_back().set_reset_match(true);
  Config* config = inputs.emplace_back().mutable_config_delta();
  config->set_auto_continue(true);
  auto& behaviour = (*config->mutable_auto_ref_configs())[kAutoRefName];
  for (GameEvent::Type type : reported_types()) {
    (*behaviour.mutable_game_event_behavior())[GameEvent::Type_Name(type)] =
        AutoRefConfig::BEHAVIOR_ACCEPT;
  }
  Input& update = inputs.emplace_back();
  update.mutable_change()->set_origin(kAutoRefName);
  auto* game = update.mutable_change()->mutable_update_config_change();
  game->set_division(setup.division_a ? DIV_A : DIV_B);
  game->set_first_kickoff_team(ssl_team(setup.first_kickoff));
  game->set_match_type(FRIENDLY);
  const bool blue_positive = setup.sides.defends(ubersim::Team::Blue) > 0;
  inputs.push_back(team_state(YELLOW, setup.yellow_name, setup.yellow_keeper, !blue_positive));
  inputs.push_back(team_state(BLUE, setup.blue_name, setup.blue_keeper, blue_positive));
  return inputs;
}

SSL_GeometryData geometry_data(const field_geometry_t& f) {
  SSL_GeometryData data;
  SSL_GeometryFieldSize* field = data.mutable_field();
  field->set_field_length(mm(f.field_length));
  field->set_field_width(mm(f.field_width));
  field->set_goal_width(mm(f.goal_width));
  field->set_goal_depth(mm(f.goal_depth));
  field->set_boundary_width(mm(f.boundary_width));
  field->set_boundary_width_goal_line(mm(f.boundary_width_goal_line));
  field->set_penalty_area_depth(mm(f.penalty_area_depth));
  field->set_penalty_area_width(mm(f.penalty_area_width));
  field->set_center_circle_radius(mm(f.center_circle_radius));
  field->set_line_thickness(mm(f.line_width));
  field->set_goal_center_to_penalty_mark(mm(f.penalty_mark_distance));
  field->set_goal_height(mm(f.goal_height));
  field->set_ball_radius(static_cast<float>(f.ball_radius * 1000));
  field->set_goal_substitution_area_width(mm(f.goal_substitution_area_width));
  return data;
}

std::optional<Input> report(const referee::GameEvent& e) {
  GameEvent event;
  event.add_origin(kAutoRefName);
  switch (e.type) {
    case EventType::Goal: {
      event.set_type(GameEvent::POSSIBLE_GOAL);
      auto* goal = event.mutable_possible_goal();
      if (e.team) goal->set_by_team(ssl_team(*e.team));
      if (e.team && e.robot >= 0) {
        goal->set_kicking_team(ssl_team(*e.team));
        goal->set_kicking_bot(static_cast<std::uint32_t>(e.robot));
      }
      if (e.has_location) set_location(*goal->mutable_location(), e);
      break;
    }
    case EventType::BallLeftFieldTouchLine:
      event.set_type(GameEvent::BALL_LEFT_FIELD_TOUCH_LINE);
      fill_foul(*event.mutable_ball_left_field_touch_line(), e);
      break;
    case EventType::BallLeftFieldGoalLine:
      event.set_type(GameEvent::BALL_LEFT_FIELD_GOAL_LINE);
      fill_foul(*event.mutable_ball_left_field_goal_line(), e);
      break;
    case EventType::AttackerDoubleTouchedBall:
      event.set_type(GameEvent::ATTACKER_DOUBLE_TOUCHED_BALL);
      fill_foul(*event.mutable_attacker_double_touched_ball(), e);
      break;
    case EventType::BotKickedBallTooFast:
      event.set_type(GameEvent::BOT_KICKED_BALL_TOO_FAST);
      fill_foul(*event.mutable_bot_kicked_ball_too_fast(), e);
      event.mutable_bot_kicked_ball_too_fast()->set_initial_ball_speed(static_cast<float>(e.value));
      break;
    case EventType::DefenderInDefenseArea:
      event.set_type(GameEvent::DEFENDER_IN_DEFENSE_AREA);
      fill_foul(*event.mutable_defender_in_defense_area(), e);
      break;
    case EventType::NoProgressInGame:
    case EventType::TooManyRobots:
      return std::nullopt;  // the GC judges these from the tracker frames itself
  }
  Input input;
  input.mutable_change()->set_origin(kAutoRefName);
  *input.mutable_change()->mutable_add_game_event_change()->mutable_game_event() = event;
  return input;
}

bool reports_wanted(const Referee& gc) {
  switch (gc.command()) {
    case Referee::NORMAL_START:
    case Referee::FORCE_START:
    case Referee::DIRECT_FREE_YELLOW:
    case Referee::DIRECT_FREE_BLUE:
      return true;
    default:
      return false;
  }
}

Input command_input(Command::Type type, ::Team team) {
  Input input;
  input.mutable_change()->set_origin(kAutoRefName);
  auto* command = input.mutable_change()->mutable_new_command_change()->mutable_command();
  command->set_type(type);
  command->set_for_team(team);
  return input;
}

Input stage_input(Referee::Stage stage) {
  Input input;
  input.mutable_change()->set_origin(kAutoRefName);
  input.mutable_change()->mutable_change_stage_change()->set_new_stage(stage);
  return input;
}

std::vector<Input> Operator::decide(const Referee& gc, double sim_time) {
  std::vector<Input> out;
  if (!started_) {  // the match starts with STOP, as the operator starts it
    started_ = true;
    out.push_back(command_input(Command::STOP));
    return out;
  }
  const bool time_up = gc.stage_time_left() <= 0;
  // Halves end when their time is up, whatever the game is doing (the GC
  // halts it); the break ends into the second half's pre-stage.
  const auto next_stage = [&]() -> std::optional<Referee::Stage> {
    switch (gc.stage()) {
      case Referee::NORMAL_FIRST_HALF:
        return Referee::NORMAL_HALF_TIME;
      case Referee::NORMAL_SECOND_HALF:
        return Referee::POST_GAME;
      case Referee::NORMAL_HALF_TIME:
        return Referee::NORMAL_SECOND_HALF_PRE;
      default:
        return std::nullopt;
    }
  }();
  if (next_stage && time_up) {
    out.push_back(stage_input(*next_stage));
    return out;
  }
  if (gc.stage() == Referee::NORMAL_HALF_TIME || gc.stage() == Referee::POST_GAME) return out;
  if (gc.command() != Referee::HALT) {
    halt_counter_.reset();
    return out;
  }
  if (halt_counter_ != gc.command_counter()) {
    halt_counter_ = gc.command_counter();
    halt_since_ = sim_time;
  }
  if (sim_time - halt_since_ >= kHaltHold) out.push_back(command_input(Command::STOP));
  return out;
}

}  // namespace ubersim::gc_link
