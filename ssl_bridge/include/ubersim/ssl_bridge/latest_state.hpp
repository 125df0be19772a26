#pragma once
// The newest SIM_STATE the bridge acts on: radio packets' t_sent, the vision
// latency of tracked frames, teleports that keep a robot's other coordinates,
// the geometry's largest robot radius. Anyone on the bus may send a state, so
// only one whose sim time physics could have sent (SimClock::valid_time:
// finite, not negative, at most 1e9 s) replaces the one kept; another is
// refused and counted, and the bridge logs it (throttled).
#include <cstdint>
#include <optional>
#include <ubersim/sim_state_t.hpp>

#include "ubersim/sim_clock.hpp"

namespace ubersim::ssl {

class LatestState {
 public:
  // False: refused, the state kept before stays.
  bool update(const sim_state_t& state) {
    if (!SimClock::valid_time(state.sim_time)) {
      ++refused_;
      return false;
    }
    state_ = state;
    return true;
  }

  const sim_state_t* get() const { return state_ ? &*state_ : nullptr; }
  // s: the kept state's time, 0 before the first.
  double sim_time() const { return state_ ? state_->sim_time : 0.0; }
  std::uint64_t refused() const { return refused_; }

 private:
  std::optional<sim_state_t> state_;
  std::uint64_t refused_ = 0;
};

}  // namespace ubersim::ssl
