#include "ubersim/referee/autoref.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <ubersim/team_t.hpp>

#include "ubersim/logging.hpp"
#include "ubersim/referee/autoref_rules.hpp"
#include "ubersim/referee/fouls.hpp"

namespace ubersim::referee {
namespace {

// The referee's placement has arrived when the ball is this close to its spot.
constexpr double kPlacedTolerance = 0.05;  // m
// A placement the simulation never carried out (refused, lost) is given up after this.
constexpr double kPlacementWait = 1.0;  // s

}  // namespace

std::string short_number(double value) {
  std::ostringstream out;
  out.precision(3);
  out << value;
  return out.str();
}

const char* stage_name(Stage stage) {
  switch (stage) {
    case Stage::FirstHalfPre:
      return "NORMAL_FIRST_HALF_PRE";
    case Stage::FirstHalf:
      return "NORMAL_FIRST_HALF";
    case Stage::HalfTime:
      return "NORMAL_HALF_TIME";
    case Stage::SecondHalfPre:
      return "NORMAL_SECOND_HALF_PRE";
    case Stage::SecondHalf:
      return "NORMAL_SECOND_HALF";
    case Stage::PostGame:
      return "POST_GAME";
  }
  return "?";
}

const char* command_name(Command command) {
  switch (command) {
    case Command::Halt:
      return "HALT";
    case Command::Stop:
      return "STOP";
    case Command::NormalStart:
      return "NORMAL_START";
    case Command::ForceStart:
      return "FORCE_START";
    case Command::PrepareKickoffYellow:
      return "PREPARE_KICKOFF_YELLOW";
    case Command::PrepareKickoffBlue:
      return "PREPARE_KICKOFF_BLUE";
    case Command::PreparePenaltyYellow:
      return "PREPARE_PENALTY_YELLOW";
    case Command::PreparePenaltyBlue:
      return "PREPARE_PENALTY_BLUE";
    case Command::DirectFreeYellow:
      return "DIRECT_FREE_YELLOW";
    case Command::DirectFreeBlue:
      return "DIRECT_FREE_BLUE";
  }
  return "?";
}

const char* event_name(EventType type) {
  switch (type) {
    case EventType::NoProgressInGame:
      return "NO_PROGRESS_IN_GAME";
    case EventType::BallLeftFieldTouchLine:
      return "BALL_LEFT_FIELD_TOUCH_LINE";
    case EventType::BallLeftFieldGoalLine:
      return "BALL_LEFT_FIELD_GOAL_LINE";
    case EventType::Goal:
      return "GOAL";
    case EventType::AttackerDoubleTouchedBall:
      return "ATTACKER_DOUBLE_TOUCHED_BALL";
    case EventType::BotKickedBallTooFast:
      return "BOT_KICKED_BALL_TOO_FAST";
    case EventType::DefenderInDefenseArea:
      return "DEFENDER_IN_DEFENSE_AREA";
    case EventType::TooManyRobots:
      return "TOO_MANY_ROBOTS";
  }
  return "?";
}

bool is_foul(EventType type) {
  switch (type) {
    case EventType::AttackerDoubleTouchedBall:
    case EventType::BotKickedBallTooFast:
    case EventType::DefenderInDefenseArea:
    case EventType::TooManyRobots:
      return true;
    case EventType::NoProgressInGame:
    case EventType::BallLeftFieldTouchLine:
    case EventType::BallLeftFieldGoalLine:
    case EventType::Goal:
      return false;
  }
  return false;
}

GameEvent make_event(EventType type, Culprit who, double x, double y, std::string description,
                     double value) {
  GameEvent event;
  event.type = type;
  event.team = who.team;
  event.robot = who.robot;
  event.has_location = true;
  event.x = x;
  event.y = y;
  event.value = value;
  event.foul = is_foul(type);
  event.description = std::move(description);
  return event;
}

Command prepare_kickoff(Team team) {
  return team == Team::Yellow ? Command::PrepareKickoffYellow : Command::PrepareKickoffBlue;
}
Command prepare_penalty(Team team) {
  return team == Team::Yellow ? Command::PreparePenaltyYellow : Command::PreparePenaltyBlue;
}
Command direct_free(Team team) {
  return team == Team::Yellow ? Command::DirectFreeYellow : Command::DirectFreeBlue;
}

AutoReferee::AutoReferee(GameConfig config, field_geometry_t field, FieldSides sides)
    : config_(config), field_(std::move(field)), sides_(sides) {}

AutoReferee::Restart AutoReferee::kickoff(Team team) const {
  Restart r;
  r.command = prepare_kickoff(team);
  r.placement = SituationRequest{Situation::KickOff, team, 0, 0};
  return r;
}

AutoReferee::Restart AutoReferee::free_kick(Team team, double x, double y) const {
  free_kick_spot(field_, x, y);
  Restart r;
  r.command = direct_free(team);
  r.placement = SituationRequest{Situation::FreeKick, team, x, y};
  return r;
}

void AutoReferee::set_command(Command command, Decision& decision) {
  state_.command = command;
  state_.command_counter++;
  state_.command_time = now_;
  decision.command_changed = true;
}

void AutoReferee::raise(GameEvent event, Decision& decision) {
  event.sim_time = now_;
  if (event.foul && event.team) state_.of(*event.team).fouls++;
  state_.events.push_back(event);
  decision.events.push_back(std::move(event));
}

// STOP now; after stop_duration the restart is placed and commanded.
void AutoReferee::stop_for(const Restart& restart, Decision& decision) {
  pending_ = restart;
  set_command(Command::Stop, decision);
  state_.next_command = restart.command;
  state_.ball_in_play = false;
  state_.action_time_left = 0;
  phase_ = Phase::Stopped;
  phase_start_ = now_;
  last_touch_.reset();
  kicker_.reset();
  // Where the restart will be: the designated position of the SSL protocol.
  state_.designated_position.reset();
  if (restart.placement) {
    const auto& p = *restart.placement;
    double x = p.x, y = p.y;
    if (p.kind == Situation::KickOff) x = y = 0;
    if (p.kind == Situation::Penalty) {
      x = penalty_mark_x(field_, sides_, p.team);
      y = 0;
    }
    state_.designated_position = std::make_pair(x, y);
  }
}

void AutoReferee::track_touches(const sim_state_t& state) {
  touching_.resize(state.robots.size(), false);
  const double bx = state.ball.position[0], by = state.ball.position[1];
  const double reach = config_.robot_radius + field_.ball_radius + config_.touch_margin;
  for (std::size_t i = 0; i < state.robots.size(); ++i) {
    const auto& r = state.robots[i];
    const bool touching = state.ball_present && state.ball.position[2] < kRobotHeight &&
                          std::hypot(r.x - bx, r.y - by) <= reach;
    if (touching && !touching_[i]) {
      last_touch_ = BallTouch{team_of(r), r.robot_id, bx, by, ++touch_counter_};
    }
    touching_[i] = touching;
  }
}

void AutoReferee::advance_clock(double dt) {
  // From the stage's end, not a sum of steps: the same at every judging rate.
  if (state_.stage == Stage::FirstHalf || state_.stage == Stage::SecondHalf ||
      state_.stage == Stage::HalfTime) {
    state_.stage_time_left = stage_end_ - now_;
  }
  if (state_.ball_in_play && last_touch_) state_.of(last_touch_->team).possession += dt;
  if (phase_ == Phase::AwaitKick) {
    state_.action_time_left = config_.restart_timeout - (now_ - phase_start_);
  }
}

bool AutoReferee::check_goal_and_out(const sim_state_t& state, Decision& decision) {
  const double x = state.ball.position[0], y = state.ball.position[1];
  const int side = goal_side(field_, x, y, state.ball.position[2]);
  // The team that last touched the ball, or (no touch since the restart) the
  // team whose half the ball is in: a deterministic owner for every out.
  const Team guilty = last_touch_
                          ? last_touch_->team
                          : (sides_.defends(Team::Yellow) * x > 0 ? Team::Yellow : Team::Blue);
  if (side != 0) {
    const Team scorer = sides_.defends(Team::Yellow) == side ? Team::Blue : Team::Yellow;
    const int robot = last_touch_ && last_touch_->team == scorer ? last_touch_->robot : -1;
    state_.of(scorer).goals++;
    raise(make_event(EventType::Goal, {scorer, robot}, x, y,
                     std::string("goal for ") + team_name(scorer) +
                         (last_touch_ && last_touch_->team != scorer ? " (own goal)" : "")),
          decision);
    stop_for(kickoff(other(scorer)), decision);
    return true;
  }
  const BallOut out = ball_out(field_, x, y);
  if (out == BallOut::No) return false;
  const EventType type = out == BallOut::TouchLine ? EventType::BallLeftFieldTouchLine
                                                   : EventType::BallLeftFieldGoalLine;
  Restart restart;
  std::string description;
  if (out == BallOut::TouchLine) {
    restart = free_kick(other(guilty), x, y);
    description = std::string("ball over the touch line, last touched by ") + team_name(guilty) +
                  ": free kick " + team_name(other(guilty));
  } else {
    const int line = x > 0 ? 1 : -1;
    const Team defending = sides_.defends(Team::Yellow) == line ? Team::Yellow : Team::Blue;
    const double corner_y = (y > 0 ? 1 : -1) * field_.field_width / 2;
    if (guilty == defending) {  // corner kick for the attackers
      restart = free_kick(other(defending), line * field_.field_length / 2, corner_y);
      description = std::string("ball over the goal line by the defending ") +
                    team_name(defending) + ": corner kick " + team_name(other(defending));
    } else {  // goal kick, 1 m from the goal line and the touch line
      restart = free_kick(defending, line * (field_.field_length / 2 - 1.0),
                          corner_y - (y > 0 ? 1 : -1) * 1.0);
      description = std::string("ball over the goal line by ") + team_name(guilty) +
                    ": goal kick " + team_name(defending);
    }
  }
  raise(make_event(type, {guilty, last_touch_ ? last_touch_->robot : -1}, x, y,
                   std::move(description)),
        decision);
  stop_for(restart, decision);
  return true;
}

void AutoReferee::check_fouls(const sim_state_t& state, Decision& decision) {
  const double bx = state.ball.position[0], by = state.ball.position[1];

  // Double touch: the kicker is bound until any robot touches the ball again.
  if (kicker_ && last_touch_ && last_touch_->id != kicker_->id) {
    const BallTouch kicker = *kicker_;
    kicker_.reset();
    if (auto foul = double_touch(kicker, *last_touch_)) {
      raise(std::move(*foul), decision);
      stop_for(free_kick(other(kicker.team), bx, by), decision);
      return;
    }
  }

  // Ball speed: a non-stopping foul, judged once per touch.
  if (last_touch_ && last_touch_->id != judged_speed_touch_) {
    if (auto foul = ball_too_fast(state, *last_touch_, config_.max_ball_speed)) {
      judged_speed_touch_ = last_touch_->id;
      raise(std::move(*foul), decision);
    }
  }

  if (auto foul = defender_in_defense_area(state, field_, sides_, config_)) {
    const Team kicking = other(*foul->team);
    raise(std::move(*foul), decision);
    Restart penalty;
    penalty.command = prepare_penalty(kicking);
    penalty.placement = SituationRequest{Situation::Penalty, kicking, 0, 0};
    stop_for(penalty, decision);
    return;
  }

  // Too many robots: repeated at most every no_progress_time while it lasts.
  for (Team team : kTeams) {
    auto& reported = too_many_reported_[static_cast<int>(team)];
    if (now_ - reported < config_.no_progress_time) continue;
    if (auto foul = too_many_robots(state, team, config_.max_robots)) {
      reported = now_;
      raise(std::move(*foul), decision);
      stop_for(free_kick(other(team), bx, by), decision);
      return;
    }
  }
}

void AutoReferee::check_shot(const sim_state_t& state) {
  if (!last_touch_ || last_touch_->id == judged_shot_touch_) return;
  const auto& v = state.ball.linear_velocity;
  if (std::hypot(v[0], v[1]) < kShotSpeed) return;
  judged_shot_touch_ = last_touch_->id;  // each touch is judged once, at its first fast ball
  const int attacked = sides_.defends(other(last_touch_->team));
  if (heads_into_goal(field_, attacked, state.ball.position[0], state.ball.position[1], v[0],
                      v[1])) {
    state_.of(last_touch_->team).shots++;
  }
}

void AutoReferee::check_no_progress(const sim_state_t& state, Decision& decision) {
  const double bx = state.ball.position[0], by = state.ball.position[1];
  if (std::hypot(bx - progress_x_, by - progress_y_) > config_.progress_distance) {
    progress_x_ = bx;
    progress_y_ = by;
    progress_time_ = now_;
    return;
  }
  if (now_ - progress_time_ < config_.no_progress_time) return;
  const double waited = now_ - progress_time_;
  raise(make_event(EventType::NoProgressInGame, {}, bx, by,
                   "no progress for " + short_number(waited) + " s: force start", waited),
        decision);
  double x = bx, y = by;
  free_kick_spot(field_, x, y);
  Restart restart;
  restart.command = Command::ForceStart;
  restart.placement = SituationRequest{Situation::BallPlacement, Team::Yellow, x, y};
  stop_for(restart, decision);
}

void AutoReferee::start_half(Stage pre_stage, Team kicking, Decision& decision) {
  state_.stage = pre_stage;
  state_.stage_time_left = 0;
  stop_for(kickoff(kicking), decision);
}

void AutoReferee::end_half(Decision& decision) {
  state_.ball_in_play = false;
  state_.next_command.reset();
  state_.designated_position.reset();
  state_.action_time_left = 0;
  set_command(Command::Halt, decision);
  if (state_.stage == Stage::FirstHalf && config_.halves == 2) {
    state_.stage = Stage::HalfTime;
    state_.stage_time_left = config_.half_time_break;
    stage_end_ = now_ + config_.half_time_break;
    phase_ = Phase::HalfTime;
  } else {
    state_.stage = Stage::PostGame;
    state_.stage_time_left = 0;
    state_.game_over = true;
    decision.game_over = true;
    phase_ = Phase::Over;
  }
  phase_start_ = now_;
}

void AutoReferee::start_play(double x, double y) {
  phase_ = Phase::Running;
  state_.ball_in_play = true;
  state_.action_time_left = 0;
  state_.events.clear();
  progress_x_ = x;
  progress_y_ = y;
  progress_time_ = now_;
}

// STOP is over: place the restart and issue its command.
void AutoReferee::issue_restart(const sim_state_t& state, Decision& decision) {
  decision.placement = pending_.placement;
  placement_pending_ = pending_.placement.has_value();
  placement_time_ = now_;
  set_command(pending_.command, decision);
  phase_start_ = now_;
  if (state_.designated_position) {
    kick_anchor_x_ = state_.designated_position->first;
    kick_anchor_y_ = state_.designated_position->second;
  } else {
    kick_anchor_x_ = state.ball.position[0];
    kick_anchor_y_ = state.ball.position[1];
  }
  if (pending_.command == Command::ForceStart) {
    state_.next_command.reset();
    start_play(kick_anchor_x_, kick_anchor_y_);
  } else if (pending_.command == Command::DirectFreeYellow ||
             pending_.command == Command::DirectFreeBlue) {
    phase_ = Phase::AwaitKick;
    state_.next_command.reset();
    state_.action_time_left = config_.restart_timeout;
  } else {
    phase_ = Phase::Prepared;
    state_.next_command = Command::NormalStart;
  }
}

// The preparation of a kick-off or penalty is over: NORMAL_START (and the
// half's clock starts with its kick-off).
void AutoReferee::normal_start(Decision& decision) {
  if (state_.stage == Stage::FirstHalfPre || state_.stage == Stage::SecondHalfPre) {
    state_.stage = state_.stage == Stage::FirstHalfPre ? Stage::FirstHalf : Stage::SecondHalf;
    state_.stage_time_left = config_.half_length();
    stage_end_ = now_ + config_.half_length();
  }
  set_command(Command::NormalStart, decision);
  state_.next_command.reset();
  phase_ = Phase::AwaitKick;
  phase_start_ = now_;
  state_.action_time_left = config_.restart_timeout;
}

// A restart is waiting to be taken: the ball in play once it left its spot,
// FORCE_START when nobody took it in time.
void AutoReferee::await_kick(const sim_state_t& state, Decision& decision) {
  if (placement_pending_) return;
  const double bx = state.ball.position[0], by = state.ball.position[1];
  const double waited = now_ - phase_start_;
  if (std::hypot(bx - kick_anchor_x_, by - kick_anchor_y_) > kKickedDistance) {
    // The robot that touched the ball last took the restart (none: nobody
    // is bound by the double-touch rule).
    kicker_ = last_touch_;
    start_play(bx, by);
  } else if (waited >= config_.restart_timeout) {
    raise(make_event(EventType::NoProgressInGame, {}, bx, by,
                     std::string(command_name(state_.command)) + " not taken within " +
                         short_number(config_.restart_timeout) + " s: force start",
                     waited),
          decision);
    set_command(Command::ForceStart, decision);
    start_play(bx, by);
  }
}

void AutoReferee::run_phase(const sim_state_t& state, Decision& decision) {
  const double in_phase = now_ - phase_start_;
  switch (phase_) {
    case Phase::Stopped:
      if (in_phase < config_.stop_duration) return;
      issue_restart(state, decision);
      return;
    case Phase::Prepared:
      if (in_phase < config_.prepare_duration) return;
      normal_start(decision);
      return;
    case Phase::AwaitKick:
      await_kick(state, decision);
      return;
    case Phase::HalfTime:
      if (state_.stage_time_left > 0) return;
      start_half(Stage::SecondHalfPre, other(config_.first_kickoff), decision);
      return;
    case Phase::Start:
    case Phase::Running:
    case Phase::Over:
      return;
  }
}

bool AutoReferee::teams_ready(const sim_state_t& state) {
  if (config_.team_wait <= 0) return true;
  if (!waiting_since_ || now_ < *waiting_since_) {  // the first state, or the simulation was reset
    waiting_since_ = now_;
    spdlog::info("HALT until every team on the field sends a command (at most {} s)",
                 config_.team_wait);
  }
  std::string silent;
  for (Team team : kTeams) {
    const bool on_field =
        std::any_of(state.robots.begin(), state.robots.end(),
                    [team](const robot_state_t& r) { return team_of(r) == team; });
    if (on_field && !heard_[static_cast<std::size_t>(team)])
      silent += std::string(" ") + team_name(team);
  }
  if (silent.empty()) return true;
  if (now_ - *waiting_since_ < config_.team_wait) return false;
  spdlog::warn("no command from{} within {} s: the game starts without waiting for it", silent,
               config_.team_wait);
  return true;
}

Decision AutoReferee::update(const sim_state_t& state) {
  Decision decision;
  if (phase_ == Phase::Over) return decision;
  // Time only moves forwards for the referee; a reset of the simulation (sim time
  // going back) just re-bases it.
  const double dt = have_time_ ? std::max(0.0, state.sim_time - now_) : 0.0;
  now_ = state.sim_time;
  have_time_ = true;

  if (phase_ == Phase::Start) {
    if (teams_ready(state)) start_half(Stage::FirstHalfPre, config_.first_kickoff, decision);
    return decision;
  }
  advance_clock(dt);

  // Until the simulation has carried out the referee's placement, the ball still lies
  // where it went out: judge nothing on it.
  if (placement_pending_) {
    const bool arrived = std::hypot(state.ball.position[0] - kick_anchor_x_,
                                    state.ball.position[1] - kick_anchor_y_) < kPlacedTolerance;
    if (arrived || now_ - placement_time_ >= kPlacementWait) {
      placement_pending_ = false;
      std::fill(touching_.begin(), touching_.end(), false);
    }
  }
  if (!placement_pending_) track_touches(state);

  const bool live = !placement_pending_ && state.ball_present &&
                    (phase_ == Phase::AwaitKick || phase_ == Phase::Running);
  bool stopped = false;
  if (live) {
    check_shot(state);
    stopped = check_goal_and_out(state, decision);
    if (!stopped && phase_ == Phase::Running) {
      check_fouls(state, decision);
      stopped = phase_ != Phase::Running;
      if (!stopped) check_no_progress(state, decision);
    }
  }
  run_phase(state, decision);

  const bool in_half = state_.stage == Stage::FirstHalf || state_.stage == Stage::SecondHalf;
  if (in_half && state_.stage_time_left <= 0) end_half(decision);
  return decision;
}

}  // namespace ubersim::referee
