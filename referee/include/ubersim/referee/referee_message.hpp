#pragma once
// The automatic referee's state on the wire (referee_t on REFEREE) and in the
// event log (one JSON object per line), both from the pure RefereeState.
#include <ostream>
#include <string>
#include <ubersim/referee_t.hpp>

#include "ubersim/referee/autoref.hpp"

namespace ubersim::referee {

referee_t to_message(const RefereeState& state, const GameConfig& config, FieldSides sides,
                     double sim_time);
referee_event_t to_message(const GameEvent& event);

// Event log lines (JSON, one object per line, keys fixed): a game event, a new
// command, and the final result with every team's figures.
std::string event_line(const GameEvent& event);
std::string command_line(const RefereeState& state, double sim_time);
std::string result_line(const RefereeState& state, double sim_time, double wall_time);

}  // namespace ubersim::referee
