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

PlaceOutcome World::place(const sim_control_t& request, bool remove_all_first) {
  PlaceOutcome outcome;
  // Check everything first: a bad request changes nothing.
  std::set<std::pair<int, int>> seen;
  std::vector<std::shared_ptr<const RobotTypeConfig>> types(request.robots.size());
  for (std::size_t i = 0; i < request.robots.size(); ++i) {
    const robot_placement_t& p = request.robots[i];
    if (p.team != 0 && p.team != 1) {
      outcome.message = "robot " + std::to_string(i) + ": unknown team " + std::to_string(p.team);
      return outcome;
    }
    const Team team = static_cast<Team>(p.team);
    if (p.robot_id < 0 || p.robot_id > kMaxRobotId) {
      outcome.message =
          "robot id " + std::to_string(p.robot_id) + " outside 0.." + std::to_string(kMaxRobotId);
      return outcome;
    }
    if (!seen.insert({p.team, p.robot_id}).second) {
      outcome.message = robot_name(team, p.robot_id) + " placed twice in one request";
      return outcome;
    }
    if (!p.present) continue;
    if (p.mode != ball_placement_t::TELEPORT && robot(team, p.robot_id) == nullptr) {
      outcome.message =
          robot_name(team, p.robot_id) + " is not on the field: it cannot move by force";
      return outcome;
    }
    if (p.mode < ball_placement_t::TELEPORT || p.mode > ball_placement_t::END_FORCE) {
      outcome.message = robot_name(team, p.robot_id) + ": unknown placement mode";
      return outcome;
    }
    for (double v : {p.x, p.y, p.orientation, p.vx, p.vy, p.omega}) {
      if (!std::isfinite(v)) {
        outcome.message = robot_name(team, p.robot_id) + ": non-finite placement";
        return outcome;
      }
    }
    if (!p.robot_type.empty()) {
      try {
        types[i] = setup_.robot_types(p.robot_type);
      } catch (const std::exception& e) {
        outcome.message =
            robot_name(team, p.robot_id) + ": robot type '" + p.robot_type + "': " + e.what();
        return outcome;
      }
    } else if (remove_all_first || robot(team, p.robot_id) == nullptr) {
      outcome.message = robot_name(team, p.robot_id) + " is new: it needs a robot_type";
      return outcome;
    }
  }
  if (request.has_ball) {
    for (double v : {request.ball.position[0], request.ball.position[1], request.ball.position[2],
                     request.ball.linear_velocity[0], request.ball.linear_velocity[1],
                     request.ball.linear_velocity[2]}) {
      if (!std::isfinite(v)) {
        outcome.message = "non-finite ball placement";
        return outcome;
      }
    }
    if (request.ball.mode < ball_placement_t::TELEPORT ||
        request.ball.mode > ball_placement_t::END_FORCE) {
      outcome.message = "unknown ball placement mode";
      return outcome;
    }
  }

  std::string notes;
  int placed = 0;
  int removed = 0;
  if (remove_all_first) {
    removed = static_cast<int>(robots_.size());
    robots_.clear();
  }
  for (std::size_t i = 0; i < request.robots.size(); ++i) {
    const robot_placement_t& p = request.robots[i];
    const Team team = static_cast<Team>(p.team);
    if (!p.present) {
      if (remove_robot(team, p.robot_id)) ++removed;
      continue;
    }
    const std::pair<int, int> key{static_cast<int>(team), p.robot_id};
    if (p.mode == ball_placement_t::BY_FORCE) {
      robot_force_[key] = ForceTarget{p.x, p.y, p.orientation};
      notes += robot_name(team, p.robot_id) + " moves by force; ";
      continue;
    }
    robot_force_.erase(key);
    if (p.mode == ball_placement_t::END_FORCE) continue;
    Robot* existing = robot(team, p.robot_id);
    const auto type = types[i] ? types[i] : existing->type_ptr();
    // Inside the walls, and no faster than the robot can go.
    const double limit_x = setup_.field.half_length_to_wall() - type->radius;
    const double limit_y = setup_.field.half_width_to_wall() - type->radius;
    PlanarState s;
    s.x = std::clamp(p.x, -limit_x, limit_x);
    s.y = std::clamp(p.y, -limit_y, limit_y);
    if (s.x != p.x || s.y != p.y)
      notes += robot_name(team, p.robot_id) + " kept inside the walls; ";
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
    ++placed;
  }
  if (request.has_ball && request.ball.mode != ball_placement_t::TELEPORT) {
    if (request.ball.mode == ball_placement_t::BY_FORCE) {
      ball_force_ = ForceTarget{request.ball.position[0], request.ball.position[1], 0};
      notes += "ball moves by force; ";
    } else {
      ball_force_.reset();
    }
  } else if (request.has_ball) {
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
