#pragma once
// Game situations a referee sets up, as robot and ball placements that obey
// the SSL rules' distances (stop: 0.5 m from the ball; kick-off: defenders
// outside the centre circle, everyone in their own half; penalty: keeper on
// the goal line, others 1 m behind the ball). Robots in the way are moved
// aside (see placement.hpp) and every placed robot is stopped.
#include <string>
#include <ubersim/field_geometry_t.hpp>

#include "ubersim/referee/placement.hpp"

namespace ubersim::referee {

enum class Situation { KickOff, FreeKick, Penalty, BallPlacement, Stop };

struct SituationRequest {
  Situation kind = Situation::Stop;
  Team team = Team::Yellow;  // the team that kicks (kick-off, free kick, penalty)
  double x = 0, y = 0;       // m, ball position for free kick and ball placement
  // Penalty: the defending team's goalkeeper (robot id) goes into the goal; -1:
  // its robot nearest to the goal (the official GC checks the declared keeper).
  int keeper = -1;
};

// Which goal each team defends: yellow defends the goal at x = yellow_defends * L/2.
struct FieldSides {
  int yellow_defends = -1;  // -1: yellow defends negative x (our scenarios' convention)
  int defends(Team team) const { return team == Team::Yellow ? yellow_defends : -yellow_defends; }
};

// SSL rule distances (m): these are the league's rules, not physics.
inline constexpr double kStopDistance = 0.5;
inline constexpr double kPenaltyBehindDistance = 1.0;
inline constexpr double kKickerGap = 0.03;
inline constexpr double kFreeKickBoundaryDistance = 0.2;

// Returns the scene after the situation's placements; throws std::runtime_error
// when the situation cannot be set up (e.g. a team has no robot on the field).
PlacementScene plan_situation(const SituationRequest& request, PlacementScene scene,
                              const field_geometry_t& field, FieldSides sides);

PlacementBounds bounds_of(const field_geometry_t& field);

// x of the penalty mark for a penalty kick by `kicking`: penalty_mark_distance
// from the centre of the goal it attacks, where the official game controller
// places the ball (x = ±(field_length / 2 - PenaltyKickDistToGoal)).
double penalty_mark_x(const field_geometry_t& field, FieldSides sides, Team kicking);

}  // namespace ubersim::referee
