// Collision of two convex polygons in the plane (separating axes, then the
// incident edge clipped against the reference face's sides).
#include "ubersim/physics/polygon_collision.hpp"

#include <algorithm>
#include <limits>

namespace ubersim::physics {
namespace {

// The start of a search for a least or greatest value.
constexpr double kUnbounded = std::numeric_limits<double>::infinity();
// Reference-face choice prefers the first polygon unless the second separates
// clearly more (keeps contacts from flickering between two nearly equal faces).
constexpr double kReferenceFaceTolerance = 1e-5;  // m, well below any contact depth that matters

// Keeps the points of segment (p[0], p[1]) with dot(normal, x) <= offset.
int clip_segment(const Vec2 in[2], Vec2 normal, double offset, Vec2 out[2]) {
  const double d0 = dot(normal, in[0]) - offset;
  const double d1 = dot(normal, in[1]) - offset;
  int n = 0;
  if (d0 <= 0) out[n++] = in[0];
  if (d1 <= 0) out[n++] = in[1];
  if (d0 * d1 < 0 && n < 2) out[n++] = in[0] + (d0 / (d0 - d1)) * (in[1] - in[0]);
  return n;
}

double max_separation(const std::vector<Vec2>& av, const std::vector<Vec2>& an,
                      const std::vector<Vec2>& bv, std::size_t* edge) {
  double best = -kUnbounded;
  std::size_t best_edge = 0;
  for (std::size_t i = 0; i < av.size(); ++i) {
    double s = kUnbounded;
    for (const Vec2& v : bv) s = std::min(s, dot(an[i], v - av[i]));
    if (s > best) {
      best = s;
      best_edge = i;
    }
  }
  *edge = best_edge;
  return best;
}

}  // namespace

bool collide_polygons(const std::vector<Vec2>& a_vertices, const std::vector<Vec2>& a_normals,
                      const std::vector<Vec2>& b_vertices, const std::vector<Vec2>& b_normals,
                      PolygonContact* contact) {
  contact->count = 0;
  std::size_t edge_a = 0;
  std::size_t edge_b = 0;
  const double sep_a = max_separation(a_vertices, a_normals, b_vertices, &edge_a);
  if (sep_a > 0) return false;
  const double sep_b = max_separation(b_vertices, b_normals, a_vertices, &edge_b);
  if (sep_b > 0) return false;

  const bool flip = sep_b > sep_a + kReferenceFaceTolerance;
  const auto& ref_v = flip ? b_vertices : a_vertices;
  const auto& ref_n = flip ? b_normals : a_normals;
  const auto& inc_v = flip ? a_vertices : b_vertices;
  const auto& inc_n = flip ? a_normals : b_normals;
  const std::size_t edge = flip ? edge_b : edge_a;
  const Vec2 n = ref_n[edge];
  const Vec2 v1 = ref_v[edge];
  const Vec2 v2 = ref_v[(edge + 1) % ref_v.size()];

  // Incident edge: the one facing the reference face most directly.
  std::size_t inc_edge = 0;
  double most_opposed = kUnbounded;
  for (std::size_t j = 0; j < inc_n.size(); ++j) {
    const double d = dot(inc_n[j], n);
    if (d < most_opposed) {
      most_opposed = d;
      inc_edge = j;
    }
  }
  const Vec2 incident[2] = {inc_v[inc_edge], inc_v[(inc_edge + 1) % inc_v.size()]};
  const Vec2 side = v2 - v1;
  const Vec2 t = (1.0 / length(side)) * side;
  Vec2 clipped1[2];
  Vec2 clipped2[2];
  int count = clip_segment(incident, -t, -dot(t, v1), clipped1);
  if (count == 2) count = clip_segment(clipped1, t, dot(t, v2), clipped2);
  if (count == 2) {
    for (const Vec2& p : clipped2) {
      const double separation = dot(n, p - v1);
      if (separation <= 0) {
        contact->points[contact->count] = p - (0.5 * separation) * n;
        contact->depths[contact->count] = -separation;
        ++contact->count;
      }
    }
  }
  if (contact->count == 0) {
    // Clipping left nothing (a corner against a short face): use the deepest vertex.
    double deepest = kUnbounded;
    Vec2 point;
    for (const Vec2& p : inc_v) {
      const double separation = dot(n, p - v1);
      if (separation < deepest) {
        deepest = separation;
        point = p;
      }
    }
    if (deepest > 0) return false;
    contact->points[0] = point - (0.5 * deepest) * n;
    contact->depths[0] = -deepest;
    contact->count = 1;
  }
  contact->normal = flip ? -n : n;
  return true;
}

}  // namespace ubersim::physics
