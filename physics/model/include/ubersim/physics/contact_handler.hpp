#pragma once
// Turns touching geoms into ODE contact joints with the surface parameters
// of the pair (friction, restitution, rolling resistance), all from config.
#include <vector>

#include "ubersim/field_config.hpp"
#include "ubersim/physics/ball.hpp"
#include "ubersim/physics/geom_tag.hpp"
#include "ubersim/physics/physics_config.hpp"

namespace ubersim::physics {

class ContactHandler {
 public:
  ContactHandler(const PhysicsConfig& physics, const FieldConfig& field, const BallConfig& ball,
                 const BallSurface& ball_surface);

  // Collides everything in `world_space` and adds the contacts to `group`.
  void collide(dSpaceID world_space, dWorldID world, dJointGroupID group);
  std::size_t contacts_last_step() const { return contacts_; }

 private:
  static void near_callback(void* data, dGeomID a, dGeomID b);
  void touch(dGeomID a, dGeomID b);
  void touch_support(dGeomID support, dGeomID ground);
  void surface_for(dGeomID a, dGeomID b, const GeomTag& ta, const GeomTag& tb, dContact& c) const;

  const PhysicsConfig& physics_;
  const FieldConfig& field_;
  const BallConfig& ball_;
  BallSurface ball_surface_;
  dWorldID world_ = nullptr;
  dJointGroupID group_ = nullptr;
  std::vector<dContactGeom> buffer_;
  std::size_t contacts_ = 0;
};

}  // namespace ubersim::physics
