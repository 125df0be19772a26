#include "ubersim/ssl_bridge/units.hpp"

#include <cmath>

namespace ubersim::ssl {

int m_to_whole_mm(double metres) {
  return static_cast<int>(std::lround(m_to_mm(metres)));
}

}  // namespace ubersim::ssl
