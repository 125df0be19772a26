#pragma once
// A body's heading in the floor plane, read from its ODE rotation matrix: the
// projection of its x axis (R[0], R[4]). Robots are kept upright, so this is
// where a robot faces; written once so that every reader agrees, including
// about a body whose x axis points straight up or down (no projection: it
// counts as heading along +x, the same as atan2(0, 0) = 0).
#include <ode/ode.h>

#include <cmath>

#include "ubersim/physics/geometry2d.hpp"

namespace ubersim::physics {

// The heading as a unit vector (cos, sin); (1, 0) when the projection vanishes.
inline Vec2 heading_direction(const dReal* R) {
  const double norm = std::hypot(R[0], R[4]);
  if (!(norm > 1e-9)) return {1.0, 0.0};
  return {R[0] / norm, R[4] / norm};
}

// The heading angle in (-pi, pi] (the published convention; atan2 alone can
// give -pi).
inline double heading_angle(const dReal* R) {
  const double angle = std::atan2(R[4], R[0]);
  return angle <= -M_PI ? angle + 2 * M_PI : angle;
}

}  // namespace ubersim::physics
