#include "ubersim/vision/sim_state_check.hpp"

#include <cmath>
#include <initializer_list>
#include <ubersim/team_t.hpp>

namespace ubersim::vision {
namespace {

constexpr double kMaxCoordinate = 1000.0;  // m: beyond this a value is garbage

bool sane(double value) {
  return std::isfinite(value) && std::abs(value) <= kMaxCoordinate;
}

bool sane3(const double (&values)[3]) {
  return sane(values[0]) && sane(values[1]) && sane(values[2]);
}

}  // namespace

std::string find_sim_state_problem(const sim_state_t& state) {
  if (!std::isfinite(state.sim_time) || state.sim_time < 0) return "sim_time is not a time >= 0";
  if (state.step < 0) return "step is negative";
  if (!std::isfinite(state.dt) || state.dt <= 0 || state.dt > 1) return "dt is not in (0, 1] s";
  if (state.ball_present && !sane3(state.ball.position)) return "ball position is not finite";
  if (state.num_robots < 0 || static_cast<std::size_t>(state.num_robots) != state.robots.size()) {
    return "num_robots does not match the robots sent";
  }
  for (const robot_state_t& robot : state.robots) {
    if (robot.team != team_t::YELLOW && robot.team != team_t::BLUE) return "a robot has no team";
    if (robot.robot_id < 0) return "a robot id is negative";
    if (!sane(robot.x) || !sane(robot.y) || !std::isfinite(robot.orientation)) {
      return "robot " + std::to_string(robot.robot_id) + " has a non-finite pose";
    }
  }
  return {};
}

std::string find_field_geometry_problem(const field_geometry_t& geometry) {
  for (double length : {geometry.field_length, geometry.field_width, geometry.boundary_width,
                        geometry.boundary_width_goal_line, geometry.goal_substitution_area_width,
                        geometry.goal_width, geometry.goal_depth}) {
    if (!std::isfinite(length) || length < 0 || length > kMaxCoordinate) {
      return "a field length is not finite and >= 0";
    }
  }
  if (!std::isfinite(geometry.ball_radius) || geometry.ball_radius < 0.005 ||
      geometry.ball_radius > 0.2) {
    return "ball_radius is not in [0.005, 0.2] m";
  }
  return {};
}

}  // namespace ubersim::vision
