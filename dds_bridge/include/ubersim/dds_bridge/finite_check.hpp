#pragma once
// FiniteCheck: remembers the path of the first non-finite real number it is
// shown; the generated non_finite_field (convert.cpp, from the .lcm files)
// shows it every real field of a message in order.
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

namespace ubersim::dds {

// "robots" and 3 -> "robots[3]".
inline std::string element(const std::string& array, std::size_t i) {
  return array + "[" + std::to_string(i) + "]";
}

class FiniteCheck {
 public:
  void operator()(const std::string& name, double value) {
    if (first_.empty() && !std::isfinite(value)) first_ = name;
  }
  template <class Real, std::size_t N>
  void operator()(const std::string& name, const Real (&values)[N]) {
    for (std::size_t i = 0; i < N; ++i) (*this)(element(name, i), values[i]);
  }
  template <class Real>
  void operator()(const std::string& name, const std::vector<Real>& values) {
    for (std::size_t i = 0; i < values.size(); ++i) (*this)(element(name, i), values[i]);
  }
  const std::string& first() const { return first_; }

 private:
  std::string first_;
};

}  // namespace ubersim::dds
