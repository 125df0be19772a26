#pragma once
// Small 2D vector maths for the planar parts of the physics (robot outlines,
// wheel placements). Kept trivial and header-only: it runs in inner loops.
#include <cmath>

namespace ubersim::physics {

struct Vec2 {
  double x = 0;
  double y = 0;
};

inline Vec2 operator+(Vec2 a, Vec2 b) {
  return {a.x + b.x, a.y + b.y};
}
inline Vec2 operator-(Vec2 a, Vec2 b) {
  return {a.x - b.x, a.y - b.y};
}
inline Vec2 operator*(double s, Vec2 a) {
  return {s * a.x, s * a.y};
}
inline Vec2 operator-(Vec2 a) {
  return {-a.x, -a.y};
}
inline double dot(Vec2 a, Vec2 b) {
  return a.x * b.x + a.y * b.y;
}
inline double cross(Vec2 a, Vec2 b) {
  return a.x * b.y - a.y * b.x;
}
inline double length(Vec2 a) {
  return std::hypot(a.x, a.y);
}
inline Vec2 rotate(Vec2 a, double c, double s) {
  return {c * a.x - s * a.y, s * a.x + c * a.y};
}
// Counter-clockwise perpendicular.
inline Vec2 perp(Vec2 a) {
  return {-a.y, a.x};
}

}  // namespace ubersim::physics
