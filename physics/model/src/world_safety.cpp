// World: keeping bodies sane (non-finite, runaway, outside the walls, tipped).
#include <algorithm>
#include <cmath>

#include "ubersim/physics/world.hpp"

namespace ubersim::physics {
namespace {

bool finite_all(const dReal* v, int n) {
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(v[i])) return false;
  }
  return true;
}

bool body_finite(dBodyID b) {
  return finite_all(dBodyGetPosition(b), 3) && finite_all(dBodyGetQuaternion(b), 4) &&
         finite_all(dBodyGetLinearVel(b), 3) && finite_all(dBodyGetAngularVel(b), 3);
}

}  // namespace

bool World::inside_walls(double x, double y, double margin) const {
  return std::abs(x) <= setup_.field.half_length_to_wall() + margin &&
         std::abs(y) <= setup_.field.half_width_to_wall() + margin;
}

bool World::body_sane(dBodyID b) const {
  if (!body_finite(b)) return false;
  const dReal* v = dBodyGetLinearVel(b);
  const dReal* w = dBodyGetAngularVel(b);
  const double max_v = setup_.physics.max_linear_speed;
  const double max_w = setup_.physics.max_angular_speed;
  return v[0] * v[0] + v[1] * v[1] + v[2] * v[2] <= max_v * max_v &&
         w[0] * w[0] + w[1] * w[1] + w[2] * w[2] <= max_w * max_w;
}

void World::check_safety(bool after_step) {
  // Beyond the walls' outer faces nothing can be legitimately. Before a step
  // this keeps a broken body away from ODE (which aborts on a non-finite
  // quaternion); after it, it keeps it out of what we publish.
  const double margin = setup_.field.wall_thickness;
  const dBodyID ball = ball_->body();
  const dReal* bp = dBodyGetPosition(ball);
  const bool ball_sane = body_sane(ball);
  if (!ball_sane || !inside_walls(bp[0], bp[1], margin) || bp[2] < -setup_.ball.radius) {
    // Over the wall or through a fault: back inside where it was last seen
    // good, on the floor, at rest.
    ++counters_.bodies_reset;
    const double r = setup_.ball.radius;
    const double x = std::clamp(ball_last_good_[0], -setup_.field.half_length_to_wall() + r,
                                setup_.field.half_length_to_wall() - r);
    const double y = std::clamp(ball_last_good_[1], -setup_.field.half_width_to_wall() + r,
                                setup_.field.half_width_to_wall() - r);
    log_.warn("reset:ball",
              std::string("ball ") +
                  (ball_sane ? "left the field" : "had a non-finite or runaway state") +
                  ": put back at (" + std::to_string(x) + ", " + std::to_string(y) + ") at rest");
    place_ball(x, y, 0, 0, 0, 0);
  } else if (after_step) {
    ball_last_good_ = {bp[0], bp[1], bp[2]};
  }

  const double upright_limit = std::cos(setup_.physics.tip_angle);
  for (auto& r : robots_) {
    body_buffer_.clear();
    r->bodies(body_buffer_);
    bool sane = true;
    for (dBodyID b : body_buffer_) sane = sane && body_sane(b);
    double x, y;
    r->position(x, y);
    if (!sane || !inside_walls(x, y, margin)) {
      ++counters_.bodies_reset;
      const PlanarState good = r->last_good_state();
      log_.warn("reset:" + robot_name(r->team(), r->id()),
                robot_name(r->team(), r->id()) +
                    (sane ? " left the field" : " had a non-finite or runaway state") +
                    ": put back at (" + std::to_string(good.x) + ", " + std::to_string(good.y) +
                    ") at rest");
      PlanarState rest = good;
      rest.vx = rest.vy = rest.omega = 0;
      r->place(rest);
      continue;
    }
    if (!after_step) continue;
    if (r->uprightness() < upright_limit) {
      ++counters_.robots_set_upright;
      log_.warn("upright:" + robot_name(r->team(), r->id()),
                robot_name(r->team(), r->id()) + " tipped over: set upright where it was");
      PlanarState rest = r->planar_state();
      rest.vx = rest.vy = rest.omega = 0;
      r->place(rest);
    }
    r->remember_good_state();
  }
}

}  // namespace ubersim::physics
