#pragma once
// The official ssl-game-controller's Referee message (224.5.23.1:10003) ->
// REFEREE (referee_t), so LCM teams, the demo team and the batch runner follow
// the same game as SSL teams when the official game controller referees
// (ubersim_ssl_bridge --official-referee, docs/official_stack.md).
//
// What the protocol does not carry is derived the way the SSL rules define it:
// the ball is in play once it moved 0.05 m from where it lay when the current
// restart command came (FORCE_START: at once); times are simulation time (the
// newest ground truth's), the game controller's wall-clock stamps are not used.
#include <ssl_gc_referee_message.pb.h>

#include <cstdint>
#include <optional>
#include <ubersim/referee_t.hpp>
#include <ubersim/sim_state_t.hpp>

namespace ubersim::ssl {

class OfficialRefereeTracker {
 public:
  // The referee_t for `referee`, judged against `state` (nullptr before the
  // first ground truth: sim time 0, ball not yet in play unless forced).
  referee_t translate(const Referee& referee, const sim_state_t* state);

 private:
  std::int64_t last_counter_ = -1;
  double command_time_ = 0;                // s, sim time the current command was first seen
  std::optional<double> command_ball_[2];  // m, where the ball lay then
  bool ball_in_play_ = false;
};

// One GameEvent of the official game controller as a referee_event_t: type,
// team, robot and location from whichever event payload is set (protobuf
// reflection: every payload names them by_team, by_bot / kicking_bot and
// location / ball_location), its message as the description.
referee_event_t from_ssl_game_event(const GameEvent& event, double sim_time);

}  // namespace ubersim::ssl
