#pragma once
#include <cmath>

namespace ubersim {

// Config files give angles in degrees (the unit in the key's name: *_DEG);
// everything inside is radians.
inline constexpr double kDegToRad = M_PI / 180.0;

// Wraps an angle to (-pi, pi], the convention of every orientation we publish.
inline double wrap_angle(double angle) {
  double wrapped = std::remainder(angle, 2.0 * M_PI);  // [-pi, pi]
  if (wrapped <= -M_PI) wrapped += 2.0 * M_PI;
  return wrapped;
}

}  // namespace ubersim
