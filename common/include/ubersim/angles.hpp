#pragma once
#include <cmath>

namespace ubersim {

// Wraps an angle to (-pi, pi], the convention of every orientation we publish.
inline double wrap_angle(double angle) {
  double wrapped = std::remainder(angle, 2.0 * M_PI);  // [-pi, pi]
  if (wrapped <= -M_PI) wrapped += 2.0 * M_PI;
  return wrapped;
}

}  // namespace ubersim
