// World: PLACE and SETUP requests (checked first, then applied), and keeping
// the ball out of robots whatever was placed where.
#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "ubersim/physics/world.hpp"

namespace ubersim::physics {
namespace {

constexpr int kMaxRobotId = 99;  // the scenario format's two-digit ids (YELLOW_0 .. BLUE_99)

}  // namespace

void World::move_ball_out_of_robots(std::string& notes) {
  const double r = setup_.ball.radius;
  for (auto& robot : robots_) {
    const dReal* bp = ball_->position();
    const PlanarState s = robot->planar_state();
    const double c = std::cos(s.heading);
    const double sn = std::sin(s.heading);
    const Vec2 local{c * (bp[0] - s.x) + sn * (bp[1] - s.y),
                     -sn * (bp[0] - s.x) + c * (bp[1] - s.y)};
    if (bp[2] > robot->type().height + r) continue;  // above it
    Vec2 closest;
    Vec2 normal;
    const double distance = robot->outline().signed_distance(local, &closest, &normal);
    if (distance >= r) continue;
    const Vec2 out_local = closest + (r + setup_.physics.contact_surface_layer) * normal;
    const Vec2 out = rotate(out_local, c, sn);
    const dReal* v = ball_->velocity();
    place_ball(s.x + out.x, s.y + out.y, bp[2], v[0], v[1], v[2]);
    notes += "ball moved out of " + robot_name(robot->team(), robot->id()) + "; ";
  }
}

namespace {

// What is wrong with the ball's part of a request; empty: nothing.
std::string check_ball_placement(const sim_control_t& request) {
  if (!request.has_ball) return "";
  for (double v : {request.ball.position[0], request.ball.position[1], request.ball.position[2],
                   request.ball.linear_velocity[0], request.ball.linear_velocity[1],
                   request.ball.linear_velocity[2]}) {
    if (!std::isfinite(v)) return "non-finite ball placement";
  }
  if (request.ball.mode < ball_placement_t::TELEPORT ||
      request.ball.mode > ball_placement_t::END_FORCE) {
    return "unknown ball placement mode";
  }
  return "";
}

}  // namespace

std::string World::check_robot_placement(const robot_placement_t& p, bool remove_all_first,
                                         std::shared_ptr<const RobotTypeConfig>& type) {
  const Team team = static_cast<Team>(p.team);
  if (p.mode != ball_placement_t::TELEPORT && robot(team, p.robot_id) == nullptr) {
    return robot_name(team, p.robot_id) + " is not on the field: it cannot move by force";
  }
  if (p.mode < ball_placement_t::TELEPORT || p.mode > ball_placement_t::END_FORCE) {
    return robot_name(team, p.robot_id) + ": unknown placement mode";
  }
  for (double v : {p.x, p.y, p.orientation, p.vx, p.vy, p.omega}) {
    if (!std::isfinite(v)) return robot_name(team, p.robot_id) + ": non-finite placement";
  }
  if (!p.robot_type.empty()) {
    try {
      type = setup_.robot_types(p.robot_type);
    } catch (const std::exception& e) {
      return robot_name(team, p.robot_id) + ": robot type '" + p.robot_type + "': " + e.what();
    }
  } else if (remove_all_first || robot(team, p.robot_id) == nullptr) {
    return robot_name(team, p.robot_id) + " is new: it needs a robot_type";
  }
  return "";
}

std::string World::check_placement(const sim_control_t& request, bool remove_all_first,
                                   std::vector<std::shared_ptr<const RobotTypeConfig>>& types) {
  std::set<std::pair<int, int>> seen;
  for (std::size_t i = 0; i < request.robots.size(); ++i) {
    const robot_placement_t& p = request.robots[i];
    if (p.team != 0 && p.team != 1) {
      return "robot " + std::to_string(i) + ": unknown team " + std::to_string(p.team);
    }
    const Team team = static_cast<Team>(p.team);
    if (p.robot_id < 0 || p.robot_id > kMaxRobotId) {
      return "robot id " + std::to_string(p.robot_id) + " outside 0.." +
             std::to_string(kMaxRobotId);
    }
    if (!seen.insert({p.team, p.robot_id}).second) {
      return robot_name(team, p.robot_id) + " placed twice in one request";
    }
    if (!p.present) continue;
    std::string problem = check_robot_placement(p, remove_all_first, types[i]);
    if (!problem.empty()) return problem;
  }
  return check_ball_placement(request);
}

bool World::apply_robot_placement(const robot_placement_t& p,
                                  std::shared_ptr<const RobotTypeConfig> type, std::string& notes) {
  const Team team = static_cast<Team>(p.team);
  const std::pair<int, int> key{static_cast<int>(team), p.robot_id};
  if (p.mode == ball_placement_t::BY_FORCE) {
    robot_force_[key] = ForceTarget{p.x, p.y, p.orientation};
    notes += robot_name(team, p.robot_id) + " moves by force; ";
    return false;
  }
  robot_force_.erase(key);
  if (p.mode == ball_placement_t::END_FORCE) return false;
  Robot* existing = robot(team, p.robot_id);
  if (!type) type = existing->type_ptr();
  // Inside the walls, and no faster than the robot can go.
  const double limit_x = setup_.field.half_length_to_wall() - type->radius;
  const double limit_y = setup_.field.half_width_to_wall() - type->radius;
  PlanarState s;
  s.x = std::clamp(p.x, -limit_x, limit_x);
  s.y = std::clamp(p.y, -limit_y, limit_y);
  if (s.x != p.x || s.y != p.y) notes += robot_name(team, p.robot_id) + " kept inside the walls; ";
  s.heading = p.orientation;
  const double speed = std::hypot(p.vx, p.vy);
  const double scale = speed > type->max_speed ? type->max_speed / speed : 1.0;
  s.vx = p.vx * scale;
  s.vy = p.vy * scale;
  s.omega = std::clamp(p.omega, -type->max_angular_speed, type->max_angular_speed);
  if (scale != 1.0 || s.omega != p.omega) {
    notes += robot_name(team, p.robot_id) + " velocity clamped to its limits; ";
  }
  if (existing != nullptr && existing->type_ptr() == type) {
    existing->place(s);
    existing->remember_good_state();
  } else {
    add_robot(team, p.robot_id, type->name, s);
  }
  return true;
}

void World::apply_ball_placement(const sim_control_t& request, std::string& notes) {
  if (request.ball.mode != ball_placement_t::TELEPORT) {
    if (request.ball.mode == ball_placement_t::BY_FORCE) {
      ball_force_ = ForceTarget{request.ball.position[0], request.ball.position[1], 0};
      notes += "ball moves by force; ";
    } else {
      ball_force_.reset();
    }
    return;
  }
  ball_force_.reset();
  const double r = setup_.ball.radius;
  const double limit_x = setup_.field.half_length_to_wall() - r;
  const double limit_y = setup_.field.half_width_to_wall() - r;
  const double x = std::clamp(request.ball.position[0], -limit_x, limit_x);
  const double y = std::clamp(request.ball.position[1], -limit_y, limit_y);
  if (x != request.ball.position[0] || y != request.ball.position[1]) {
    notes += "ball kept inside the walls; ";
  }
  place_ball(x, y, request.ball.position[2], request.ball.linear_velocity[0],
             request.ball.linear_velocity[1], request.ball.linear_velocity[2]);
  if (request.ball.rolling) {
    // Rolling without slipping on the floor: v = w x (r z).
    dBodySetAngularVel(ball_->body(), -request.ball.linear_velocity[1] / r,
                       request.ball.linear_velocity[0] / r, 0);
  }
}

PlaceOutcome World::place(const sim_control_t& request, bool remove_all_first) {
  PlaceOutcome outcome;
  // Check everything first: a bad request changes nothing.
  std::vector<std::shared_ptr<const RobotTypeConfig>> types(request.robots.size());
  outcome.message = check_placement(request, remove_all_first, types);
  if (!outcome.message.empty()) return outcome;

  std::string notes;
  int placed = 0;
  int removed = 0;
  if (remove_all_first) {
    removed = static_cast<int>(robots_.size());
    robots_.clear();
  }
  for (std::size_t i = 0; i < request.robots.size(); ++i) {
    const robot_placement_t& p = request.robots[i];
    if (!p.present) {
      if (remove_robot(static_cast<Team>(p.team), p.robot_id)) ++removed;
      continue;
    }
    if (apply_robot_placement(p, types[i], notes)) ++placed;
  }
  if (request.has_ball) apply_ball_placement(request, notes);
  // Wherever robots and ball ended up, the ball is never left inside a robot.
  move_ball_out_of_robots(notes);
  std::ostringstream message;
  message << "placed " << placed << " robot(s), removed " << removed;
  if (request.has_ball) message << ", placed the ball";
  if (!notes.empty()) message << "; " << notes.substr(0, notes.size() - 2);
  outcome.ok = true;
  outcome.message = message.str();
  return outcome;
}

}  // namespace ubersim::physics
