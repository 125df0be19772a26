#pragma once
// The field geometry behind the automatic referee's rules, as plain functions
// of positions: is the ball in a goal, out, is a robot inside a defence area,
// where may a free kick be taken, does a kick head for a goal. "Side" is the
// sign of x of a goal line: -1 the negative-x goal, +1 the positive-x goal.
#include <ubersim/field_geometry_t.hpp>

namespace ubersim::referee {

enum class BallOut { No, TouchLine, GoalLine };

// The ball counts as kicked (a restart taken) once it left its spot by this much.
inline constexpr double kKickedDistance = 0.05;  // m
// A kick faster than this whose path enters the goal mouth is a shot.
inline constexpr double kShotSpeed = 1.5;  // m/s
// A ball higher than this cannot touch a robot (SSL robots are at most 0.15 m).
inline constexpr double kRobotHeight = 0.15;  // m

// How far the ball's centre is from being wholly over a touch line or a goal
// line (m; <= 0: it is over one). Goals and outs both start there.
double distance_to_out(const field_geometry_t& field, double x, double y);

// The whole ball is over a goal line between the posts and below the crossbar:
// returns that goal's side, else 0.
int goal_side(const field_geometry_t& field, double x, double y, double z);

// The whole ball is over a touch line or a goal line (outside a goal's mouth).
BallOut ball_out(const field_geometry_t& field, double x, double y);

// The whole robot (a disc of `radius`) is inside the defence area at `side`.
bool fully_in_defense_area(const field_geometry_t& field, int side, double x, double y,
                           double radius);

// Nearest place to (x, y) where the SSL rules let a free kick be taken: 0.2 m
// inside the field lines and 0.2 m outside either defence area.
void free_kick_spot(const field_geometry_t& field, double& x, double& y);

// A ball at (x, y) moving with (vx, vy) crosses the goal line at `side`
// between the posts (straight-line path, moving towards it).
bool heads_into_goal(const field_geometry_t& field, int side, double x, double y, double vx,
                     double vy);

}  // namespace ubersim::referee
