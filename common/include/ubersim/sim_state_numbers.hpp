#pragma once
// Whether a SIM_STATE's numbers are ones physics could have sent: a valid sim
// time, and every position, velocity and angle of the ball and the robots
// finite and within 1e9 (m, m/s, rad, rad/s), far beyond any field. Anyone on
// the bus may send another; the readers that compute with those numbers (the
// referee's judge, the SSL bridge's tracked frames) refuse it, so that no NaN
// or infinity reaches what they publish.
#include <cmath>
#include <ubersim/sim_state_t.hpp>

#include "ubersim/sim_clock.hpp"

namespace ubersim {

inline constexpr double kMaxStateNumber = 1e9;

inline bool state_number_fits(double value) {
  return std::isfinite(value) && std::abs(value) <= kMaxStateNumber;
}

inline bool sim_state_numbers_fit(const sim_state_t& state) {
  bool ok = SimClock::valid_time(state.sim_time);
  for (int i = 0; i < 3; ++i) {
    ok = ok && state_number_fits(state.ball.position[i]) &&
         state_number_fits(state.ball.linear_velocity[i]) &&
         state_number_fits(state.ball.angular_velocity[i]);
  }
  for (const robot_state_t& r : state.robots) {
    ok = ok && state_number_fits(r.x) && state_number_fits(r.y) &&
         state_number_fits(r.orientation) && state_number_fits(r.vx) && state_number_fits(r.vy) &&
         state_number_fits(r.omega);
  }
  return ok;
}

}  // namespace ubersim
