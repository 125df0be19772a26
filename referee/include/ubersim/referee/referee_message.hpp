#pragma once
// The automatic referee's state on the wire (referee_t on REFEREE) and in the
// event log (one JSON object per line), both from the pure RefereeState.
#include <ostream>
#include <string>
#include <ubersim/referee_t.hpp>
#include <ubersim/sync_status_t.hpp>
#include <vector>

#include "ubersim/referee/autoref.hpp"

namespace ubersim::referee {

referee_t to_message(const RefereeState& state, const GameConfig& config, FieldSides sides,
                     double sim_time);
referee_event_t to_message(const GameEvent& event);

// Event log lines (JSON, one object per line, keys fixed): a game event, a new
// command, and the final result with every team's figures.
std::string event_line(const GameEvent& event);
std::string command_line(const RefereeState& state, double sim_time);
// A team that played part of a sync run without control: its sync client was
// dropped (SIM_SYNC_STATUS, docs/sync.md "A dropped client").
struct ControlLoss {
  std::string team;
  std::string client;
  int drops = 0;
  double without_control = 0;  // s of sim time, up to the end of the game
};
// The teams that lost control before `end` (s of sim time), from the latest status.
std::vector<ControlLoss> control_losses(const sync_status_t& status, double end);
// "DEGRADED: yellow without control for 12.3 s of sim time (...)"; "" when none.
std::string degraded_text(const std::vector<ControlLoss>& losses);

// The result line; with losses, a "degraded" list before the wall time.
std::string result_line(const RefereeState& state, double sim_time, double wall_time,
                        const std::vector<ControlLoss>& losses = {});

}  // namespace ubersim::referee
