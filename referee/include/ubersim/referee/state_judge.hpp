#pragma once
// What `ubersim_referee auto` does with one SIM_STATE, without the bus: which
// states it judges, the AutoReferee's decision, and what goes out because of
// it (referee_t on REFEREE, a placement on SIM_CONTROL, event log lines).
// AutoRefShell puts it on the bus; fuzz_lcm_consumers feeds it hostile states.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <ubersim/field_geometry_t.hpp>
#include <ubersim/referee_t.hpp>
#include <ubersim/sim_control_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <vector>

#include "ubersim/referee/autoref.hpp"

namespace ubersim::referee {

struct JudgeOptions {
  GameConfig game;
  FieldSides sides;
  bool sync = false;              // REFEREE after every state judged
  bool judge_every_step = false;  // judge every state, not only those next_judge_time names
};

// What one SIM_STATE makes the referee send.
struct JudgeOutput {
  bool judged = false;                     // false: the state was skipped
  std::vector<std::string> log_lines;      // event log (JSON lines), in order
  std::optional<sim_control_t> placement;  // SIM_CONTROL PLACE; request_id and sender unset
  std::optional<referee_t> referee;        // REFEREE
  bool game_over = false;                  // the game just ended
};

class StateJudge {
 public:
  // radius_of: a robot type's radius (m), for the placement.
  StateJudge(JudgeOptions options, field_geometry_t field,
             std::function<double(const std::string&)> radius_of);

  // A state with a sim time that is not valid (SimClock::valid_time) or a
  // number that is not finite or beyond 1e9 is not judged (refused()): what
  // it holds would go out in REFEREE or a placement.
  JudgeOutput on_state(const sim_state_t& state);
  // A team sent a command (AutoReferee::team_heard).
  void team_heard(Team team) { referee_.team_heard(team); }

  // The field changed at run time: placements and rules follow it.
  void set_field(const field_geometry_t& field) {
    field_ = field;
    referee_.set_field(field);
  }

  const RefereeState& state() const { return referee_.state(); }
  double last_time() const { return last_time_; }  // s, of the last state judged
  std::uint64_t judged() const { return judged_; }
  std::uint64_t refused() const { return refused_; }

 private:
  // Whether this state is judged: the first at or after the time the referee
  // named (the simulation in sync mode sends that one), or after a reset.
  bool judges(const sim_state_t& state) const;
  std::optional<sim_control_t> place(const SituationRequest& request, const sim_state_t& state);

  JudgeOptions options_;
  field_geometry_t field_;
  std::function<double(const std::string&)> radius_of_;
  AutoReferee referee_;
  double last_publish_ = -1e9;
  double last_time_ = 0;
  double next_judge_ = 0;  // s: the state to judge next
  std::uint64_t judged_ = 0;
  std::uint64_t refused_ = 0;
  bool judged_any_ = false;
};

}  // namespace ubersim::referee
