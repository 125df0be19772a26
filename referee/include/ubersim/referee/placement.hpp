#pragma once
// Moves robots apart so that no two bodies overlap and every robot keeps its
// required distance from the ball, staying inside the walls. Robots marked
// fixed (e.g. a kicker or keeper the referee placed on purpose) do not move;
// everyone else moves as little as the constraints need. Deterministic.
#include <vector>

#include "ubersim/channels.hpp"

namespace ubersim::referee {

struct PlacedRobot {
  Team team = Team::Yellow;
  int id = 0;
  double radius = 0.09;      // m
  double x = 0, y = 0;       // m
  double orientation = 0;    // rad
  double ball_keep_out = 0;  // m, minimum distance of the robot's centre from the ball's centre
  double min_x = -1e9;       // m, limits on the centre's x (e.g. "stay in your own half")
  double max_x = 1e9;        // m
  bool fixed = false;
};

struct PlacementBounds {
  double half_length = 0;  // m, robots' centres stay within |x| <= half_length - radius
  double half_width = 0;   // m
};

struct PlacementScene {
  std::vector<PlacedRobot> robots;
  double ball_x = 0, ball_y = 0;  // m
  double ball_radius = 0.0215;    // m
};

// Minimum gap left between two robots' hulls (m).
inline constexpr double kRobotGap = 0.02;

// Returns true when every constraint holds afterwards.
bool separate(PlacementScene& scene, const PlacementBounds& bounds);

// True when no robots overlap, none is closer to the ball than its keep-out,
// and all are inside the bounds (tolerance 1 mm).
bool is_legal(const PlacementScene& scene, const PlacementBounds& bounds);

}  // namespace ubersim::referee
