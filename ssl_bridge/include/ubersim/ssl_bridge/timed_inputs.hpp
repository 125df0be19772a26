#pragma once
// What the SSL bridge hands team programs under the time shim waits for its
// sim time (docs/timeshim.md, "Integration with sync mode"). Two rules, one
// place: which held messages are due, and up to which time every message of
// the referee and the radio is here.
#include <algorithm>
#include <deque>
#include <iterator>
#include <vector>

namespace ubersim::ssl {

// Moves the messages stamped up to t (s of sim time) out of `held`, in the
// order they came; the later ones stay, in order.
template <class Msg, class Stamp>
std::vector<Msg> take_until(std::vector<Msg>& held, double t, const Stamp& stamp) {
  const auto later =
      std::stable_partition(held.begin(), held.end(), [&](const Msg& m) { return stamp(m) <= t; });
  std::vector<Msg> due(std::make_move_iterator(held.begin()), std::make_move_iterator(later));
  held.erase(held.begin(), later);
  return due;
}

// The latest of `state_times` (the sim times of the states physics published)
// before `publication`, or -1 when there is none. The referee (with
// --sync-referee) and, for a timed client, the radio's feedback links hold
// physics at each state they must answer until they did: so what they said
// of the states before a frame's publication came before the frame (one
// socket, in order); of the state at the publication itself they may not
// have spoken yet.
inline double latest_before(const std::deque<double>& state_times, double publication) {
  double latest = -1;
  for (double t : state_times) {
    if (t < publication) latest = std::max(latest, t);
  }
  return latest;
}

}  // namespace ubersim::ssl
