#pragma once
// Collision of two convex polygons in the plane: robots against robots and
// against walls, seen from above.
#include <vector>

#include "ubersim/physics/geometry2d.hpp"

namespace ubersim::physics {

// 2D collision of two convex polygons (counter-clockwise,
// with outward edge normals). normal points from a to b; up to 2 points.
struct PolygonContact {
  Vec2 normal;
  int count = 0;
  Vec2 points[2];
  double depths[2] = {0, 0};
};
bool collide_polygons(const std::vector<Vec2>& a_vertices, const std::vector<Vec2>& a_normals,
                      const std::vector<Vec2>& b_vertices, const std::vector<Vec2>& b_normals,
                      PolygonContact* contact);

}  // namespace ubersim::physics
