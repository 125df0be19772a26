#pragma once
// The automatic referee: pure game logic. It takes ground truth (sim_state_t,
// one per simulation step or fewer) and the field geometry, and returns what a
// game controller plus an autoref would decide: the referee command and stage,
// score, game events, and the ball/robot placement that starts each restart.
// No LCM in here: `ubersim_referee auto` (AutoRefShell) puts it on the bus, and
// every rule has a unit test that builds the situation and checks the decision.
//
// Numbering of stages, commands and event types is that of the SSL game
// controller's protocol (ssl_gc_referee_message.proto, ssl_gc_game_event.proto),
// so they go out as SSL messages without a translation table.
#include <array>
#include <optional>
#include <string>
#include <ubersim/field_geometry_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <vector>

#include "ubersim/channels.hpp"
#include "ubersim/referee/autoref_config.hpp"
#include "ubersim/referee/situations.hpp"

namespace ubersim::referee {

// Referee.Stage (only the normal-time stages are used).
enum class Stage : int {
  FirstHalfPre = 0,
  FirstHalf = 1,
  HalfTime = 2,
  SecondHalfPre = 3,
  SecondHalf = 4,
  PostGame = 13,
};

// Referee.Command.
enum class Command : int {
  Halt = 0,
  Stop = 1,
  NormalStart = 2,
  ForceStart = 3,
  PrepareKickoffYellow = 4,
  PrepareKickoffBlue = 5,
  PreparePenaltyYellow = 6,
  PreparePenaltyBlue = 7,
  DirectFreeYellow = 8,
  DirectFreeBlue = 9,
};

// GameEvent.Type of the events this referee raises.
enum class EventType : int {
  NoProgressInGame = 2,
  BallLeftFieldTouchLine = 6,
  BallLeftFieldGoalLine = 7,
  Goal = 8,
  AttackerDoubleTouchedBall = 14,
  BotKickedBallTooFast = 18,
  DefenderInDefenseArea = 31,
  TooManyRobots = 38,
};

const char* stage_name(Stage stage);
const char* command_name(Command command);
const char* event_name(EventType type);
Command prepare_kickoff(Team team);
Command prepare_penalty(Team team);
Command direct_free(Team team);
inline Team other(Team team) {
  return team == Team::Yellow ? Team::Blue : Team::Yellow;
}

struct GameEvent {
  EventType type = EventType::Goal;
  double sim_time = 0;       // s
  std::optional<Team> team;  // scoring team for a goal, the guilty team otherwise
  int robot = -1;            // robot id, -1 = none
  bool has_location = false;
  double x = 0, y = 0;      // m, where it happened
  double value = 0;         // ball speed (m/s) for too fast; robots on field for too many
  bool foul = false;        // counts as a foul of `team`
  std::string description;  // one line for people and the event log
};

// Whom an event names: the scoring team of a goal, the guilty team (and
// robot) of a foul or an out; nobody for no progress.
struct Culprit {
  std::optional<Team> team;
  int robot = -1;  // robot id, -1 = none
};

// The fouls among the event types (they count against the culprit's team).
bool is_foul(EventType type);

// The one place a GameEvent is made: every event this referee raises happened
// at a place on the field (x, y in m). `value` as in GameEvent. The sim time
// is added when the event is raised.
GameEvent make_event(EventType type, Culprit who, double x, double y, std::string description,
                     double value = 0);

// A number for an event's description: 3 significant digits ("6.52", "10").
std::string short_number(double value);

// A robot touching the ball: who, and where the ball was (m). `id` counts
// touches, so that each touch is judged once.
struct BallTouch {
  Team team = Team::Yellow;
  int robot = -1;
  double x = 0, y = 0;
  int id = 0;
};

struct TeamStats {
  int goals = 0;
  int shots = 0;  // kicks whose straight path enters the opponent goal mouth
  int fouls = 0;
  double possession = 0;  // s of ball-in-play time this team touched the ball last
};

struct RefereeState {
  Stage stage = Stage::FirstHalfPre;
  Command command = Command::Halt;
  std::optional<Command> next_command;
  int command_counter = 0;
  double command_time = 0;      // sim time of the current command (s)
  double stage_time_left = 0;   // s
  double action_time_left = 0;  // s left for the restart to be taken (0 when none)
  bool ball_in_play = false;    // the game is running (the last restart was taken)
  std::optional<std::pair<double, double>> designated_position;  // m, of the current restart
  TeamStats yellow, blue;
  std::vector<GameEvent> events;  // since the ball was last in play (SSL: game_events)
  bool game_over = false;

  TeamStats& of(Team team) { return team == Team::Yellow ? yellow : blue; }
  const TeamStats& of(Team team) const { return team == Team::Yellow ? yellow : blue; }
};

// What one update decided.
struct Decision {
  std::vector<GameEvent> events;              // new events, in order
  std::optional<SituationRequest> placement;  // referee places ball and robots (ball placement)
  bool command_changed = false;
  bool game_over = false;  // the game just ended
};

class AutoReferee {
 public:
  AutoReferee(GameConfig config, field_geometry_t field, FieldSides sides = {});

  Decision update(const sim_state_t& state);

  // A team sent a command: before the game starts the referee holds HALT until every team
  // with robots on the field has (GameConfig::team_wait).
  void team_heard(Team team) { heard_[static_cast<std::size_t>(team)] = true; }

  // The field changed at run time (a SIM_GEOMETRY that differs, e.g. the
  // geometry a SET_FIELD applied): rules and restart spots use it from now on.
  void set_field(const field_geometry_t& field) { field_ = field; }
  const field_geometry_t& field() const { return field_; }

  // Sim time of the next state this referee must judge, after update(state):
  // no rule can decide differently on any state before it, given how fast
  // the ball and the robots can move and when its clocks run out, so judging
  // only the states it names decides exactly as judging every state
  // (docs/autoref.md, "Judging rate"). A step of state.dt at least, at most
  // kMaxJudgePeriod.
  double next_judge_time(const sim_state_t& state) const;
  static constexpr double kMaxJudgePeriod = 0.1;  // s: REFEREE at 10 Hz at least

  const RefereeState& state() const { return state_; }
  const GameConfig& config() const { return config_; }

 private:
  // Where the game is between commands.
  enum class Phase { Start, Stopped, Prepared, AwaitKick, Running, HalfTime, Over };
  bool teams_ready(const sim_state_t& state);
  std::array<bool, 2> heard_{};
  std::optional<double> waiting_since_;  // sim time the referee began to wait for the teams
  struct Restart {
    Command command =
        Command::ForceStart;  // PrepareKickoff*, PreparePenalty*, DirectFree*, ForceStart
    std::optional<SituationRequest> placement;
  };
  void set_command(Command command, Decision& decision);
  void stop_for(const Restart& restart, Decision& decision);
  void raise(GameEvent event, Decision& decision);
  void track_touches(const sim_state_t& state);
  void advance_clock(double dt);

  bool check_goal_and_out(const sim_state_t& state, Decision& decision);
  void check_fouls(const sim_state_t& state, Decision& decision);
  void check_shot(const sim_state_t& state);
  void check_no_progress(const sim_state_t& state, Decision& decision);
  void run_phase(const sim_state_t& state, Decision& decision);
  void issue_restart(const sim_state_t& state, Decision& decision);
  void normal_start(Decision& decision);
  void await_kick(const sim_state_t& state, Decision& decision);
  // The ball is in play from (x, y), where no-progress is measured from.
  void start_play(double x, double y);
  void start_half(Stage pre_stage, Team kicking, Decision& decision);
  void end_half(Decision& decision);

  // A free kick for `team` at (x, y), moved where the rules allow one.
  Restart free_kick(Team team, double x, double y) const;
  Restart kickoff(Team team) const;

  GameConfig config_;
  field_geometry_t field_;
  FieldSides sides_;
  RefereeState state_;
  Phase phase_ = Phase::Start;
  double now_ = 0;
  double phase_start_ = 0;
  bool have_time_ = false;
  Restart pending_;
  std::optional<BallTouch> last_touch_;
  std::optional<BallTouch>
      kicker_;                  // took the last kick-off / free kick; no other robot touched since
  std::vector<bool> touching_;  // per robot index of the last state
  int touch_counter_ = 0;
  bool placement_pending_ = false;  // placed, and the simulation has not shown it yet
  double placement_time_ = 0;       // s
  int judged_speed_touch_ = -1;
  int judged_shot_touch_ = -1;
  double kick_anchor_x_ = 0, kick_anchor_y_ = 0;  // ball at the restart (m)
  double progress_x_ = 0, progress_y_ = 0;        // ball when it last moved (m)
  double progress_time_ = 0;                      // s
  double too_many_reported_[2] = {-1e9, -1e9};    // sim time of the last report per team
  double stage_end_ = 0;                          // s, of a half or the half-time break
};

}  // namespace ubersim::referee
