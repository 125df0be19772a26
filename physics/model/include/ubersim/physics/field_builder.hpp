#pragma once
// The static part of the world: the floor, the boundary walls and both goals
// of any configured field, as ODE geoms without bodies.
#include <deque>
#include <vector>

#include "ubersim/field_config.hpp"
#include "ubersim/physics/geom_tag.hpp"
#include "ubersim/physics/ode_handles.hpp"

namespace ubersim::physics {

struct StaticField {
  SpaceHandle space;  // walls and goals
  GeomHandle ground;  // the floor plane z = 0, directly in the world space
  std::vector<GeomHandle> walls;
  GeomTag ground_tag{GeomKind::Ground};
  GeomTag wall_tag{GeomKind::Wall};
};

// Builds the field into `world_space`. The returned object must not move
// while the geoms live (their tags point into it), hence the unique_ptr.
std::unique_ptr<StaticField> build_field(const FieldConfig& field, dSpaceID world_space);

}  // namespace ubersim::physics
