#include "ubersim/physics/chassis_geom.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <stdexcept>

#include "ubersim/physics/heading.hpp"

namespace ubersim::physics {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

struct ChassisGeomData {
  const ChassisOutline* outline;
};

int g_chassis_class = -1;

dContactGeom* contact_at(dContactGeom* contacts, int skip, int index) {
  return reinterpret_cast<dContactGeom*>(reinterpret_cast<char*>(contacts) +
                                         static_cast<std::ptrdiff_t>(index) * skip);
}

// Local -> world for an ODE rotation (3x4, row-major).
void to_world(const dReal* pos, const dReal* R, double x, double y, double z, double out[3]) {
  out[0] = pos[0] + R[0] * x + R[1] * y + R[2] * z;
  out[1] = pos[1] + R[4] * x + R[5] * y + R[6] * z;
  out[2] = pos[2] + R[8] * x + R[9] * y + R[10] * z;
}

// The outline in the world's floor plane: the chassis is upright in every
// case that matters (a tipped robot is set upright), so its heading is the
// projection of its x axis.
void outline_in_plane(const ChassisOutline& o, const dReal* pos, const dReal* R,
                      std::vector<Vec2>& vertices, std::vector<Vec2>& normals) {
  const Vec2 heading = heading_direction(R);
  const double c = heading.x;
  const double s = heading.y;
  const Vec2 origin{pos[0], pos[1]};
  vertices.resize(o.vertices.size());
  normals.resize(o.normals.size());
  for (std::size_t i = 0; i < o.vertices.size(); ++i) {
    vertices[i] = origin + rotate(o.vertices[i], c, s);
    normals[i] = rotate(o.normals[i], c, s);
  }
}

// World z range a chassis may occupy (exact when upright, conservative tilted).
void chassis_z_range(const ChassisOutline& o, const dReal* pos, const dReal* R, double* lo,
                     double* hi) {
  const double a = R[10] * o.z_bottom;
  const double b = R[10] * o.z_top;
  const double spread = (std::abs(R[8]) + std::abs(R[9])) * o.bounding_radius;
  *lo = pos[2] + std::min(a, b) - spread;
  *hi = pos[2] + std::max(a, b) + spread;
}

const ChassisOutline& outline_of(dGeomID g) {
  return *static_cast<ChassisGeomData*>(dGeomGetClassData(g))->outline;
}

void aabb(dGeomID g, dReal box[6]) {
  const ChassisOutline& o = outline_of(g);
  const dReal* pos = dGeomGetPosition(g);
  const dReal* R = dGeomGetRotation(g);
  const double zmid = (o.z_bottom + o.z_top) / 2;
  const double half_height = (o.z_top - o.z_bottom) / 2;
  const double r = std::sqrt(o.bounding_radius * o.bounding_radius + half_height * half_height);
  double c[3];
  to_world(pos, R, 0, 0, zmid, c);
  box[0] = c[0] - r;
  box[1] = c[0] + r;
  box[2] = c[1] - r;
  box[3] = c[1] + r;
  box[4] = c[2] - r;
  box[5] = c[2] + r;
}

// Writes 2D polygon contacts as ODE contacts at height z (normal into o1).
int emit_plane_contacts(const PolygonContact& pc, double z, dGeomID o1, dGeomID o2, int flags,
                        dContactGeom* contacts, int skip) {
  const int max_contacts = std::max(1, flags & 0xffff);
  int n = 0;
  for (int i = 0; i < pc.count && n < max_contacts; ++i) {
    dContactGeom* c = contact_at(contacts, skip, n++);
    c->pos[0] = pc.points[i].x;
    c->pos[1] = pc.points[i].y;
    c->pos[2] = z;
    c->normal[0] = -pc.normal.x;
    c->normal[1] = -pc.normal.y;
    c->normal[2] = 0;
    c->depth = pc.depths[i];
    c->g1 = o1;
    c->g2 = o2;
    c->side1 = -1;
    c->side2 = -1;
  }
  return n;
}

int collide_chassis_chassis(dGeomID o1, dGeomID o2, int flags, dContactGeom* contacts, int skip) {
  const ChassisOutline& a = outline_of(o1);
  const ChassisOutline& b = outline_of(o2);
  const dReal* pa = dGeomGetPosition(o1);
  const dReal* Ra = dGeomGetRotation(o1);
  const dReal* pb = dGeomGetPosition(o2);
  const dReal* Rb = dGeomGetRotation(o2);
  double lo_a, hi_a, lo_b, hi_b;
  chassis_z_range(a, pa, Ra, &lo_a, &hi_a);
  chassis_z_range(b, pb, Rb, &lo_b, &hi_b);
  const double lo = std::max(lo_a, lo_b);
  const double hi = std::min(hi_a, hi_b);
  if (hi <= lo) return 0;
  // Bounding circles apart: nothing to do (the common case near other robots).
  const double dx = pa[0] - pb[0], dy = pa[1] - pb[1];
  const double reach = a.bounding_radius + b.bounding_radius;
  if (dx * dx + dy * dy > reach * reach) return 0;
  thread_local std::vector<Vec2> av, an, bv, bn;
  outline_in_plane(a, pa, Ra, av, an);
  outline_in_plane(b, pb, Rb, bv, bn);
  PolygonContact pc;
  if (!collide_polygons(av, an, bv, bn, &pc)) return 0;
  return emit_plane_contacts(pc, (lo + hi) / 2, o1, o2, flags, contacts, skip);
}

int collide_chassis_box(dGeomID o1, dGeomID o2, int flags, dContactGeom* contacts, int skip) {
  const ChassisOutline& a = outline_of(o1);
  const dReal* pa = dGeomGetPosition(o1);
  const dReal* Ra = dGeomGetRotation(o1);
  dVector3 lengths;
  dGeomBoxGetLengths(o2, lengths);
  const dReal* pb = dGeomGetPosition(o2);
  const dReal* Rb = dGeomGetRotation(o2);
  // Boxes here are walls and goals: upright, so their outline is a rectangle.
  double lo_a, hi_a;
  chassis_z_range(a, pa, Ra, &lo_a, &hi_a);
  const double lo = std::max(lo_a, pb[2] - lengths[2] / 2);
  const double hi = std::min(hi_a, pb[2] + lengths[2] / 2);
  if (hi <= lo) return 0;
  const Vec2 ax{Rb[0], Rb[4]};
  const Vec2 ay{Rb[1], Rb[5]};
  const Vec2 c{pb[0], pb[1]};
  const double hx = lengths[0] / 2;
  const double hy = lengths[1] / 2;
  // Bounding circle clear of the rectangle: nothing to do.
  const Vec2 rel = Vec2{pa[0], pa[1]} - c;
  const double ex = std::max(0.0, std::abs(dot(rel, ax)) - hx);
  const double ey = std::max(0.0, std::abs(dot(rel, ay)) - hy);
  if (ex * ex + ey * ey > a.bounding_radius * a.bounding_radius) return 0;
  thread_local std::vector<Vec2> av, an;
  thread_local std::vector<Vec2> bv(4), bn(4);
  bv[0] = c - hx * ax - hy * ay;
  bv[1] = c + hx * ax - hy * ay;
  bv[2] = c + hx * ax + hy * ay;
  bv[3] = c - hx * ax + hy * ay;
  bn[0] = -ay;
  bn[1] = ax;
  bn[2] = ay;
  bn[3] = -ax;
  outline_in_plane(a, pa, Ra, av, an);
  PolygonContact pc;
  if (!collide_polygons(av, an, bv, bn, &pc)) return 0;
  return emit_plane_contacts(pc, (lo + hi) / 2, o1, o2, flags, contacts, skip);
}

int collide_chassis_sphere(dGeomID o1, dGeomID o2, int /*flags*/, dContactGeom* contacts,
                           int /*skip*/) {
  const ChassisOutline& o = outline_of(o1);
  const dReal* pos = dGeomGetPosition(o1);
  const dReal* R = dGeomGetRotation(o1);
  const dReal* centre = dGeomGetPosition(o2);
  const double radius = dGeomSphereGetRadius(o2);
  // Sphere centre in the chassis frame (R^T (c - pos)).
  const double d[3] = {centre[0] - pos[0], centre[1] - pos[1], centre[2] - pos[2]};
  const double p[3] = {R[0] * d[0] + R[4] * d[1] + R[8] * d[2],
                       R[1] * d[0] + R[5] * d[1] + R[9] * d[2],
                       R[2] * d[0] + R[6] * d[1] + R[10] * d[2]};
  Vec2 closest;
  Vec2 side_normal;
  const double side_distance = o.signed_distance({p[0], p[1]}, &closest, &side_normal);
  const bool inside_z = p[2] >= o.z_bottom && p[2] <= o.z_top;
  double normal[3];  // chassis frame, from the chassis towards the sphere centre
  double surface[3];
  double depth;
  if (side_distance < 0 && inside_z) {
    // Centre inside the prism: leave through the nearest face.
    const double to_top = o.z_top - p[2];
    const double to_bottom = p[2] - o.z_bottom;
    const double to_side = -side_distance;
    if (to_side <= to_top && to_side <= to_bottom) {
      normal[0] = side_normal.x;
      normal[1] = side_normal.y;
      normal[2] = 0;
      surface[0] = closest.x;
      surface[1] = closest.y;
      surface[2] = p[2];
      depth = to_side + radius;
    } else if (to_top <= to_bottom) {
      normal[0] = 0;
      normal[1] = 0;
      normal[2] = 1;
      surface[0] = p[0];
      surface[1] = p[1];
      surface[2] = o.z_top;
      depth = to_top + radius;
    } else {
      normal[0] = 0;
      normal[1] = 0;
      normal[2] = -1;
      surface[0] = p[0];
      surface[1] = p[1];
      surface[2] = o.z_bottom;
      depth = to_bottom + radius;
    }
  } else {
    surface[0] = side_distance < 0 ? p[0] : closest.x;
    surface[1] = side_distance < 0 ? p[1] : closest.y;
    surface[2] = std::clamp(p[2], o.z_bottom, o.z_top);
    const double diff[3] = {p[0] - surface[0], p[1] - surface[1], p[2] - surface[2]};
    const double dist = std::sqrt(diff[0] * diff[0] + diff[1] * diff[1] + diff[2] * diff[2]);
    if (dist >= radius) return 0;
    if (dist > 1e-12) {
      normal[0] = diff[0] / dist;
      normal[1] = diff[1] / dist;
      normal[2] = diff[2] / dist;
    } else {
      // Centre exactly on the surface: use the side's normal.
      normal[0] = side_normal.x;
      normal[1] = side_normal.y;
      normal[2] = 0;
    }
    depth = radius - dist;
  }
  dContactGeom* c = contacts;
  double world_surface[3];
  to_world(pos, R, surface[0], surface[1], surface[2], world_surface);
  // Normal into o1 (the chassis): from the sphere towards the chassis.
  c->normal[0] = -(R[0] * normal[0] + R[1] * normal[1] + R[2] * normal[2]);
  c->normal[1] = -(R[4] * normal[0] + R[5] * normal[1] + R[6] * normal[2]);
  c->normal[2] = -(R[8] * normal[0] + R[9] * normal[1] + R[10] * normal[2]);
  c->pos[0] = world_surface[0];
  c->pos[1] = world_surface[1];
  c->pos[2] = world_surface[2];
  c->depth = depth;
  c->g1 = o1;
  c->g2 = o2;
  c->side1 = -1;
  c->side2 = -1;
  return 1;
}

int collide_chassis_plane(dGeomID o1, dGeomID o2, int flags, dContactGeom* contacts, int skip) {
  const ChassisOutline& o = outline_of(o1);
  const dReal* pos = dGeomGetPosition(o1);
  const dReal* R = dGeomGetRotation(o1);
  dVector4 plane;
  dGeomPlaneGetParams(o2, plane);
  // Lowest reach of the prism along the plane's normal: its axis' extent plus
  // the outline's radius in the directions across the axis.
  const double zmid = (o.z_bottom + o.z_top) / 2;
  const double half_height = (o.z_top - o.z_bottom) / 2;
  double centre[3];
  to_world(pos, R, 0, 0, zmid, centre);
  const double n_x = plane[0] * R[0] + plane[1] * R[4] + plane[2] * R[8];
  const double n_y = plane[0] * R[1] + plane[1] * R[5] + plane[2] * R[9];
  const double n_z = plane[0] * R[2] + plane[1] * R[6] + plane[2] * R[10];
  const double reach =
      std::abs(n_z) * half_height + std::sqrt(n_x * n_x + n_y * n_y) * o.bounding_radius;
  if (plane[0] * centre[0] + plane[1] * centre[1] + plane[2] * centre[2] - plane[3] > reach) {
    return 0;
  }
  struct Candidate {
    double depth;
    std::size_t index;
    double pos[3];
  };
  thread_local std::vector<Candidate> candidates;
  candidates.clear();
  const double rings[2] = {o.z_bottom, o.z_top};
  std::size_t index = 0;
  for (double z : rings) {
    for (const Vec2& v : o.vertices) {
      Candidate cand;
      to_world(pos, R, v.x, v.y, z, cand.pos);
      cand.depth =
          plane[3] - (plane[0] * cand.pos[0] + plane[1] * cand.pos[1] + plane[2] * cand.pos[2]);
      cand.index = index++;
      if (cand.depth > 0) candidates.push_back(cand);
    }
  }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    return a.depth != b.depth ? a.depth > b.depth : a.index < b.index;
  });
  const int max_contacts = std::max(1, flags & 0xffff);
  int n = 0;
  for (const Candidate& cand : candidates) {
    if (n >= max_contacts) break;
    dContactGeom* c = contact_at(contacts, skip, n++);
    c->pos[0] = cand.pos[0];
    c->pos[1] = cand.pos[1];
    c->pos[2] = cand.pos[2];
    c->normal[0] = plane[0];
    c->normal[1] = plane[1];
    c->normal[2] = plane[2];
    c->depth = cand.depth;
    c->g1 = o1;
    c->g2 = o2;
    c->side1 = -1;
    c->side2 = -1;
  }
  return n;
}

dColliderFn* collider_for(int other_class) {
  switch (other_class) {
    case dSphereClass:
      return collide_chassis_sphere;
    case dBoxClass:
      return collide_chassis_box;
    case dPlaneClass:
      return collide_chassis_plane;
    default:
      return nullptr;
  }
}

}  // namespace

ChassisOutline ChassisOutline::make(double radius, double front_distance, int segments,
                                    double z_bottom, double z_top) {
  if (segments < 3) throw std::invalid_argument("a chassis outline needs at least 3 segments");
  ChassisOutline o;
  o.z_bottom = z_bottom;
  o.z_top = z_top;
  const double half_front =
      std::sqrt(std::max(0.0, radius * radius - front_distance * front_distance));
  const bool flat_front = half_front > 1e-6 * radius;
  const double start = flat_front ? std::atan2(half_front, front_distance) : 0.0;
  const double end = flat_front ? 2 * M_PI - start : 2 * M_PI;
  const int corners =
      flat_front ? segments + 1 : segments;  // a full circle does not repeat its start
  for (int i = 0; i < corners; ++i) {
    const double a = start + (end - start) * i / segments;
    o.vertices.push_back({radius * std::cos(a), radius * std::sin(a)});
  }
  return polygon(std::move(o.vertices), z_bottom, z_top);
}

ChassisOutline ChassisOutline::polygon(std::vector<Vec2> vertices, double z_bottom, double z_top) {
  if (vertices.size() < 3) throw std::invalid_argument("a chassis outline needs 3 corners");
  ChassisOutline o;
  o.z_bottom = z_bottom;
  o.z_top = z_top;
  o.vertices = std::move(vertices);
  for (std::size_t i = 0; i < o.vertices.size(); ++i) {
    const Vec2 e = o.vertices[(i + 1) % o.vertices.size()] - o.vertices[i];
    const double len = length(e);
    if (!(len > 0)) throw std::invalid_argument("a chassis outline has two equal corners");
    o.normals.push_back({e.y / len, -e.x / len});
    o.bounding_radius = std::max(o.bounding_radius, length(o.vertices[i]));
  }
  return o;
}

double ChassisOutline::signed_distance(Vec2 p, Vec2* closest, Vec2* outward_normal) const {
  const std::size_t n = vertices.size();
  double max_d = -kInfinity;
  std::size_t max_edge = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double d = dot(normals[i], p - vertices[i]);
    if (d > max_d) {
      max_d = d;
      max_edge = i;
    }
  }
  if (max_d <= 0) {
    // Inside: the edge of least penetration.
    *outward_normal = normals[max_edge];
    *closest = p - max_d * normals[max_edge];
    return max_d;
  }
  double best = kInfinity;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = vertices[i];
    const Vec2 e = vertices[(i + 1) % n] - a;
    const double t = std::clamp(dot(p - a, e) / dot(e, e), 0.0, 1.0);
    const Vec2 q = a + t * e;
    const double dist = length(p - q);
    if (dist < best) {
      best = dist;
      *closest = q;
    }
  }
  const Vec2 away = p - *closest;
  *outward_normal = best > 1e-12 ? (1.0 / best) * away : normals[max_edge];
  return best;
}

int chassis_geom_class() {
  static std::once_flag once;
  std::call_once(once, [] {
    dGeomClass c{};
    c.bytes = sizeof(ChassisGeomData);
    c.collider = collider_for;
    c.aabb = aabb;
    c.aabb_test = nullptr;
    c.dtor = nullptr;
    g_chassis_class = dCreateGeomClass(&c);
    dSetColliderOverride(g_chassis_class, g_chassis_class, collide_chassis_chassis);
  });
  return g_chassis_class;
}

dGeomID create_chassis_geom(dSpaceID space, const ChassisOutline* outline) {
  dGeomID g = dCreateGeom(chassis_geom_class());
  static_cast<ChassisGeomData*>(dGeomGetClassData(g))->outline = outline;
  if (space != nullptr) dSpaceAdd(space, g);
  return g;
}

const ChassisOutline* chassis_outline_of(dGeomID geom) {
  if (dGeomGetClass(geom) != g_chassis_class) return nullptr;
  return &outline_of(geom);
}

}  // namespace ubersim::physics
