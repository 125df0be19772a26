#pragma once
// One detector per foul the automatic referee judges (docs/autoref.md, "Rules
// and decisions"). Each looks at one state of the game and returns the foul's
// event, or nothing: it only decides. AutoReferee keeps the memory (which
// touch was judged, when a foul was last reported) and gives the restart.
#include <optional>
#include <ubersim/field_geometry_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <ubersim/team_t.hpp>

#include "ubersim/referee/autoref.hpp"
#include "ubersim/referee/autoref_config.hpp"
#include "ubersim/referee/situations.hpp"

namespace ubersim::referee {

// The team a robot of a simulation state plays for.
inline Team team_of(const robot_state_t& robot) {
  return robot.team == team_t::BLUE ? Team::Blue : Team::Yellow;
}

// The robot that took a kick-off or free kick (`kicker`) touched the ball
// again (`last_touch`, a later touch) before any other robot did. The event is
// placed where it took the restart, as the SSL event has it.
std::optional<GameEvent> double_touch(const BallTouch& kicker, const BallTouch& last_touch);

// The ball is faster than `max_ball_speed` (m/s): the robot that touched it
// last kicked it too fast. The event's value is the ball's speed.
std::optional<GameEvent> ball_too_fast(const sim_state_t& state, const BallTouch& last_touch,
                                       double max_ball_speed);

// A robot other than its team's keeper, wholly inside its own defence area,
// touches the ball (below robot height); the first such robot in state order.
std::optional<GameEvent> defender_in_defense_area(const sim_state_t& state,
                                                  const field_geometry_t& field,
                                                  const FieldSides& sides,
                                                  const GameConfig& config);

// `team` has more than `max_robots` robots on the field. The event is placed
// where the ball is; its value is the number of robots.
std::optional<GameEvent> too_many_robots(const sim_state_t& state, Team team, int max_robots);

}  // namespace ubersim::referee
