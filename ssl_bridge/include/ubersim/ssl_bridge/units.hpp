#pragma once
// Exact unit conversions between ubersim (SI: m, rad, rad/s) and the SSL
// protocols (SSL-Vision: mm; simulation protocol: degrees for kick angles, rpm
// for the dribbler). One place, so every conversion is tested once.
#include "ubersim/sim_state_numbers.hpp"

namespace ubersim::ssl {

inline constexpr double kPi = 3.14159265358979323846;

constexpr double m_to_mm(double metres) {
  return metres * 1000.0;
}
constexpr double mm_to_m(double millimetres) {
  return millimetres / 1000.0;
}
constexpr double deg_to_rad(double degrees) {
  return degrees * (kPi / 180.0);
}
constexpr double rad_to_deg(double radians) {
  return radians * (180.0 / kPi);
}
// Revolutions per minute <-> angular speed: 1 rpm = 2 pi rad / 60 s.
constexpr double rpm_to_rad_per_s(double rpm) {
  return rpm * (2.0 * kPi / 60.0);
}
constexpr double rad_per_s_to_rpm(double rad_per_s) {
  return rad_per_s * (60.0 / (2.0 * kPi));
}

// A number from LCM the bridge may put in an SSL packet: finite, and at most
// 1e9 (m, px, rad, s, m/s), far beyond any field and far within SSL's float
// millimetres. ubersim's own processes never send another; anyone on the bus
// may. The same bound as a SIM_STATE's numbers (sim_state_numbers.hpp).
inline bool fits_ssl(double value) {
  return state_number_fits(value);
}

// Field sizes in SSL geometry are whole millimetres (int32).
int m_to_whole_mm(double metres);

}  // namespace ubersim::ssl
