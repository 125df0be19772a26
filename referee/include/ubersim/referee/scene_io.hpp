#pragma once
// Between the wire and the placement solver: ground truth -> PlacementScene,
// and a planned scene -> the sim_control_t PLACE that makes it so.
#include <functional>
#include <string>
#include <ubersim/sim_control_t.hpp>
#include <ubersim/sim_state_t.hpp>

#include "ubersim/referee/placement.hpp"

namespace ubersim::referee {

// radius_of(robot_type) gives each robot's radius (m).
PlacementScene scene_from_state(const sim_state_t& state, double ball_radius,
                                const std::function<double(const std::string&)>& radius_of);

// One robot's placement on the wire, stopped.
robot_placement_t to_placement(const PlacedRobot& robot);

// A PLACE request for the ball (when place_ball) and for every robot of
// `planned` that moved from `before` by more than 1 mm, or all robots when
// `all_robots`; each placed robot is stopped.
sim_control_t place_request(const PlacementScene& before, const PlacementScene& planned,
                            bool place_ball, bool all_robots);

}  // namespace ubersim::referee
