#pragma once
// The automatic referee's game settings: game length, pauses, the rule limits
// it judges by. Read from config/referee/*.cfg (our config format), so an
// experiment can change any of them like any other key.
#include <string>

#include "ubersim/channels.hpp"
#include "ubersim/config.hpp"

namespace ubersim::referee {

struct GameConfig {
  double game_length = 600;        // s of sim time, both halves together
  int halves = 2;                  // 1 or 2
  double half_time_break = 1;      // s
  double stop_duration = 2;        // s of STOP before each restart
  double prepare_duration = 1;     // s from PREPARE_* to NORMAL_START
  double restart_timeout = 10;     // s for a kick-off or free kick to be taken, then FORCE_START
  double no_progress_time = 10;    // s without the ball moving before NO_PROGRESS_IN_GAME
  double progress_distance = 0.1;  // m the ball must move to count as progress
  int max_robots = 6;              // per team on the field
  double max_ball_speed = 6.5;     // m/s
  double robot_radius = 0.09;      // m, for touches and the defence area rule
  double touch_margin = 0.015;     // m between hull and ball that still counts as a touch
  int keeper_yellow = 0;           // robot ids of the keepers
  int keeper_blue = 0;
  Team first_kickoff = Team::Yellow;
  // TeamInfo.name on REFEREE (YELLOW_NAME / BLUE_NAME, --yellow-name / --blue-name). Not empty:
  // an SSL AI that finds its colour by name finds none in an empty name.
  std::string yellow_name = "Yellow";
  std::string blue_name = "Blue";
  // s of sim time the referee holds HALT before the first STOP until every team with robots on
  // the field has sent a command (`ubersim_referee auto --team-wait`): an SSL AI leaves its own
  // halt only on the referee's STOP, so it must be listening when STOP comes. 0: start at once.
  double team_wait = 0;

  int keeper(Team team) const { return team == Team::Yellow ? keeper_yellow : keeper_blue; }
  double half_length() const { return halves == 2 ? game_length / 2 : game_length; }
};

// What is wrong with `name` as a team name (empty when nothing): 1..64 bytes, no control
// characters.
std::string team_name_problem(const std::string& name);

// Reads every key (GAME_LENGTH, HALVES, ...; YELLOW_NAME and BLUE_NAME may be left out: Yellow,
// Blue); unknown keys are errors.
GameConfig load_game_config(const ConfigFile& file);
GameConfig load_game_config(const std::string& config_dir, const std::string& name);

}  // namespace ubersim::referee
