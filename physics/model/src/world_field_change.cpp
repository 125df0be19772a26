// The field changed at run time (SIM_CONTROL SET_FIELD), e.g. the geometry a
// team sends over the SSL simulation protocol: the static field is rebuilt
// in the same ODE world, and robots and ball left outside the new walls are
// put back inside them.
#include <algorithm>
#include <memory>
#include <vector>

#include "ubersim/field_change.hpp"
#include "ubersim/physics/world.hpp"

namespace ubersim::physics {

void World::change_ball_radius(double radius) {
  BallConfig ball = setup_.ball;
  ball.radius = radius;
  // The robots first: a type whose dribbler cannot touch such a ball throws
  // here, before anything changed.
  std::vector<std::unique_ptr<Robot>> rebuilt;
  for (const auto& old : robots_) {
    rebuilt.push_back(std::make_unique<Robot>(world_.get(), space_.get(), setup_.physics, ball,
                                              old->type_ptr(), old->team(), old->id()));
    rebuilt.back()->place(old->planar_state());
    rebuilt.back()->remember_good_state();
  }
  robots_ = std::move(rebuilt);

  const dReal* p = ball_->position();
  const dReal* v = ball_->velocity();
  const double bottom = p[2] - setup_.ball.radius;
  const double at[3] = {p[0], p[1], std::max(bottom, 0.0) + radius};
  const double velocity[3] = {v[0], v[1], v[2]};
  setup_.ball = ball;
  ball_surface_ = derive_ball_surface(setup_.ball, setup_.physics.gravity);
  ball_.reset();
  ball_ = std::make_unique<Ball>(world_.get(), space_.get(), setup_.ball, ball_surface_);
  contact_handler_ =
      std::make_unique<ContactHandler>(setup_.physics, setup_.field, setup_.ball, ball_surface_);
  place_ball(at[0], at[1], at[2], velocity[0], velocity[1], velocity[2]);
}

std::string World::change_field(const std::string& field_text) {
  const FieldChange change = change_field_and_ball(setup_.field, field_text);
  std::string ball_note;
  if (change.ball_radius && *change.ball_radius != setup_.ball.radius) {
    change_ball_radius(*change.ball_radius);
    ball_note = "ball radius now " + std::to_string(*change.ball_radius) + " m; ";
  }
  const FieldConfig& changed = change.field;
  setup_.field = changed;
  field_.reset();
  field_ = build_field(setup_.field, space_.get());
  // The contact handler keeps a reference to setup_.field (updated in place);
  // it is rebuilt anyway, so no cached value of the old field survives.
  contact_handler_ =
      std::make_unique<ContactHandler>(setup_.physics, setup_.field, setup_.ball, ball_surface_);
  int moved = 0;
  for (const auto& robot : robots_) {
    PlanarState s = robot->planar_state();
    const double lx = setup_.field.half_length_to_wall() - robot->type().radius;
    const double ly = setup_.field.half_width_to_wall() - robot->type().radius;
    const double x = std::clamp(s.x, -lx, lx), y = std::clamp(s.y, -ly, ly);
    if (x == s.x && y == s.y) continue;
    s.x = x;
    s.y = y;
    s.vx = s.vy = s.omega = 0;
    robot->place(s);
    robot->remember_good_state();
    ++moved;
  }
  const dReal* p = ball_->position();
  const double r = setup_.ball.radius;
  const double bx = std::clamp(static_cast<double>(p[0]), -(setup_.field.half_length_to_wall() - r),
                               setup_.field.half_length_to_wall() - r);
  const double by = std::clamp(static_cast<double>(p[1]), -(setup_.field.half_width_to_wall() - r),
                               setup_.field.half_width_to_wall() - r);
  if (bx != p[0] || by != p[1]) {
    place_ball(bx, by, 0, 0, 0, 0);
    ++moved;
  }
  std::string notes;
  move_ball_out_of_robots(notes);
  return ball_note + "field now " + std::to_string(setup_.field.field_length) + " x " +
         std::to_string(setup_.field.field_width) + " m; " + std::to_string(moved) +
         " bodies moved inside the walls";
}

}  // namespace ubersim::physics
