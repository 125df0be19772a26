#include "ubersim/referee/scene_io.hpp"

#include <cmath>
#include <ubersim/team_t.hpp>

namespace ubersim::referee {

PlacementScene scene_from_state(const sim_state_t& state, double ball_radius,
                                const std::function<double(const std::string&)>& radius_of) {
  PlacementScene scene;
  scene.ball_x = state.ball.position[0];
  scene.ball_y = state.ball.position[1];
  scene.ball_radius = ball_radius;
  for (const auto& r : state.robots) {
    PlacedRobot robot;
    robot.team = r.team == team_t::BLUE ? Team::Blue : Team::Yellow;
    robot.id = r.robot_id;
    robot.radius = radius_of(r.robot_type);
    robot.x = r.x;
    robot.y = r.y;
    robot.orientation = r.orientation;
    scene.robots.push_back(robot);
  }
  return scene;
}

robot_placement_t to_placement(const PlacedRobot& robot) {
  robot_placement_t placement{};
  placement.team = robot.team == Team::Blue ? team_t::BLUE : team_t::YELLOW;
  placement.robot_id = robot.id;
  placement.present = true;
  placement.x = robot.x;
  placement.y = robot.y;
  placement.orientation = robot.orientation;
  return placement;
}

sim_control_t place_request(const PlacementScene& before, const PlacementScene& planned,
                            bool place_ball, bool all_robots) {
  sim_control_t control{};
  control.action = sim_control_t::PLACE;
  for (std::size_t i = 0; i < planned.robots.size(); ++i) {
    const auto& p = planned.robots[i];
    const bool moved = i >= before.robots.size() ||
                       std::hypot(p.x - before.robots[i].x, p.y - before.robots[i].y) > 1e-3 ||
                       std::abs(p.orientation - before.robots[i].orientation) > 1e-3;
    if (!all_robots && !moved) continue;
    control.robots.push_back(to_placement(p));
  }
  control.num_robots = static_cast<int32_t>(control.robots.size());
  control.has_ball = place_ball;
  control.ball.position[0] = planned.ball_x;
  control.ball.position[1] = planned.ball_y;
  return control;
}

}  // namespace ubersim::referee
