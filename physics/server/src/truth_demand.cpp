#include "ubersim/physics/truth_demand.hpp"

#include <algorithm>
#include <cmath>

namespace ubersim::physics {

void TruthDemand::published(double t) {
  if (!recent_.empty() && t < recent_.back()) recent_.clear();  // sim time went back: a reset
  recent_.push_back(t);
  if (recent_.size() > 4096) recent_.pop_front();
}

std::string TruthDemand::on_demand(const truth_demand_t& d, double now, double dt,
                                   Clock::time_point wall) {
  if (d.consumer.empty()) return "no consumer name";
  if (d.num_periodic < 0 || d.num_instants < 0 || d.num_periodic > kMaxEntries ||
      d.num_instants > kMaxEntries || d.period.size() != static_cast<std::size_t>(d.num_periodic) ||
      d.phase.size() != d.period.size() ||
      d.instants.size() != static_cast<std::size_t>(d.num_instants)) {
    return "bad counts";
  }
  if (consumers_.count(d.consumer) == 0 && consumers_.size() >= kMaxConsumers) {
    return "too many consumers";
  }
  Consumer c;
  c.every_step = d.every_step;
  c.heard = wall;
  for (std::size_t i = 0; i < d.period.size(); ++i) {
    // A period under 0.1 ms would be every step anyway; refuse nonsense.
    if (!std::isfinite(d.period[i]) || !std::isfinite(d.phase[i]) || d.period[i] < 1e-4) {
      return "bad period";
    }
    c.periodic.emplace_back(d.period[i], d.phase[i]);
  }
  for (double t : d.instants) {
    if (!std::isfinite(t)) return "bad instant";
    if (t <= now - kTolerance) {
      // Physics is past it. Served already if the state of the first step at
      // or after it went out; else the demand came late: the next state serves it.
      const auto served = std::lower_bound(recent_.begin(), recent_.end(), t - kTolerance);
      if (served == recent_.end() || *served >= t - kTolerance + dt) {
        ++late_;
        catch_up_ = true;
      }
      continue;
    }
    c.instants.insert(t);
  }
  consumers_[d.consumer] = std::move(c);
  return "";
}

bool TruthDemand::wanted(double t, double dt) {
  bool want = catch_up_;
  catch_up_ = false;
  for (auto& [name, c] : consumers_) {
    if (c.every_step) want = true;
    for (const auto& [period, phase] : c.periodic) {
      // The last instant at or before t: is it after the previous step?
      const double n = std::floor((t + kTolerance - phase) / period);
      if (n >= 0 && phase + n * period > t - dt + kTolerance) want = true;
    }
    while (!c.instants.empty() && *c.instants.begin() <= t + kTolerance) {
      c.instants.erase(c.instants.begin());
      want = true;
    }
  }
  return want;
}

bool TruthDemand::would_want(double t, double dt) const {
  if (catch_up_) return true;
  for (const auto& [name, c] : consumers_) {
    if (c.every_step) return true;
    for (const auto& [period, phase] : c.periodic) {
      const double n = std::floor((t + kTolerance - phase) / period);
      if (n >= 0 && phase + n * period > t - dt + kTolerance) return true;
    }
    if (!c.instants.empty() && *c.instants.begin() <= t + kTolerance) return true;
  }
  return false;
}

std::vector<std::string> TruthDemand::expire(Clock::time_point wall, Clock::duration silence) {
  std::vector<std::string> gone;
  for (auto it = consumers_.begin(); it != consumers_.end();) {
    if (wall - it->second.heard > silence) {
      gone.push_back(it->first);
      it = consumers_.erase(it);
    } else {
      ++it;
    }
  }
  return gone;
}

void TruthDemand::reset() {
  for (auto& [name, c] : consumers_) c.instants.clear();
  catch_up_ = false;
}

}  // namespace ubersim::physics
