#pragma once
// `ubersim_referee auto`: the automatic referee on the bus. It judges the
// SIM_STATEs where a rule could decide (AutoReferee::next_judge_time), publishes referee_t on
// REFEREE (on each change and at 10 Hz of sim time), carries out each restart's placement through
// the safe placement (SIM_CONTROL PLACE), and writes the event log. Its shell (AutoRefShell, around
// the StateJudge core) runs on the process host (docs/design.md, "One shape for every program") and
// returns when the game is over (or on SIGINT/SIGTERM).
#include <string>

#include "ubersim/common_options.hpp"
#include "ubersim/referee/autoref.hpp"

namespace ubersim::referee {

struct AutoOptions {
  CommonOptions common;
  GameConfig game;
  FieldSides sides;
  std::string events_file;     // event log (JSON lines); empty: none
  double timeout_s = 2.0;      // for the field geometry at the start
  bool exit_at_end = true;     // return once the game is over
  bool start_physics = false;  // send RESUME once listening (physics started --paused)
  // Sync mode: REFEREE after every state judged; a physics started with
  // --sync-referee steps only up to the state the referee judges next.
  bool sync = false;
  // Judge every state, not only those AutoReferee::next_judge_time names.
  bool judge_every_step = false;
  // A new game starts kNewGamePause after each one is over, until stopped (the
  // demo: it never simply ends). Not with sync, where physics holds at the end.
  bool repeat = false;
};

// s of sim time between the end of a game and the next one's start (repeat):
// the final score stays on REFEREE, everyone halted, this long.
inline constexpr double kNewGamePause = 5.0;

// Returns 0 after a finished game (or a clean stop), 1 on an error.
int run_auto_referee(const AutoOptions& options);

}  // namespace ubersim::referee
