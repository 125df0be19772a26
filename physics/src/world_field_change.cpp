// The field changed at run time (SIM_CONTROL SET_FIELD), e.g. the geometry a
// team sends over the SSL simulation protocol: the static field is rebuilt
// in the same ODE world, and robots and ball left outside the new walls are
// put back inside them.
#include <algorithm>

#include "ubersim/field_change.hpp"
#include "ubersim/physics/world.hpp"

namespace ubersim::physics {

std::string World::change_field(const std::string& field_text) {
  const FieldConfig changed = ubersim::change_field(setup_.field, field_text);
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
  return "field now " + std::to_string(setup_.field.field_length) + " x " +
         std::to_string(setup_.field.field_width) + " m; " + std::to_string(moved) +
         " bodies moved inside the walls";
}

}  // namespace ubersim::physics
