#pragma once
// The chassis of every robot is an upright prism over a convex outline: the
// SSL shape, a circle with its front cut flat. ODE cannot collide cylinders
// with cylinders well, so the chassis is a geom class of our own with exact
// colliders against spheres (ball, 3D), boxes (walls and goals), the floor
// plane and other chassis (both in the floor plane, where robots live).
#include <ode/ode.h>

#include <vector>

#include "ubersim/physics/geometry2d.hpp"
#include "ubersim/physics/polygon_collision.hpp"

namespace ubersim::physics {

struct ChassisOutline {
  std::vector<Vec2> vertices;  // counter-clockwise, chassis frame (x forward), m
  std::vector<Vec2> normals;   // outward unit normal of the edge vertices[i] -> vertices[i+1]
  double z_bottom = 0;         // m, underside relative to the geom origin
  double z_top = 0;            // m, top relative to the geom origin
  double bounding_radius = 0;  // m, farthest vertex from the z axis

  // A circle of `radius` cut flat at x = front_distance, the round part split
  // into `segments` straight pieces whose corners lie on the circle.
  static ChassisOutline make(double radius, double front_distance, int segments, double z_bottom,
                             double z_top);
  // Any convex polygon (corners counter-clockwise), e.g. a part of the front
  // around the kicker's mouth.
  static ChassisOutline polygon(std::vector<Vec2> vertices, double z_bottom, double z_top);

  // Signed distance from a point (chassis frame) to the outline: < 0 inside.
  // `edge` gets the edge of least penetration (inside) or nearest (outside).
  double signed_distance(Vec2 p, Vec2* closest, Vec2* outward_normal) const;
};

// The geom class, registered with ODE on first use.
int chassis_geom_class();
// A chassis geom in `space`. `outline` must outlive the geom.
dGeomID create_chassis_geom(dSpaceID space, const ChassisOutline* outline);
const ChassisOutline* chassis_outline_of(dGeomID geom);

}  // namespace ubersim::physics
