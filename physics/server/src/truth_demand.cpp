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
  const auto known = consumers_.find(d.consumer);
  if (known != consumers_.end() && known->second.own) return "the name of one of physics' own";
  const bool is_new = known == consumers_.end();
  if (is_new && programs_ >= static_cast<std::size_t>(kMaxConsumers)) return "too many consumers";
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
  if (is_new) ++programs_;
  return "";
}

TruthDemand::Consumer& TruthDemand::own(const std::string& name, While when) {
  Consumer& c = consumers_[name];
  c = Consumer{};
  c.own = true;
  c.when = when;
  return c;
}

void TruthDemand::own_every_step(const std::string& name, While when) {
  own(name, when).every_step = true;
}

void TruthDemand::own_periodic(const std::string& name, double period, double phase, While when) {
  own(name, when).periodic.emplace_back(period, phase);
}

void TruthDemand::own_from(const std::string& name, double from) {
  own(name, While::Always).from = from;
}

bool TruthDemand::periodic_due(const Consumer& c, double t, double dt) {
  for (const auto& [period, phase] : c.periodic) {
    // The last instant at or before t: is it after the previous step?
    const double n = std::floor((t + kTolerance - phase) / period);
    if (n >= 0 && phase + n * period > t - dt + kTolerance) return true;
  }
  return false;
}

bool TruthDemand::wanted(double t, double dt) {
  bool want = catch_up_;
  catch_up_ = false;
  for (auto& [name, c] : consumers_) {
    if (!counts(c)) continue;
    if (c.every_step || t + dt * 1e-6 >= c.from || periodic_due(c, t, dt)) want = true;
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
    if (!counts(c)) continue;
    if (c.every_step || t + dt * 1e-6 >= c.from || periodic_due(c, t, dt)) return true;
    if (!c.instants.empty() && *c.instants.begin() <= t + kTolerance) return true;
  }
  return false;
}

std::vector<std::string> TruthDemand::expire(Clock::time_point wall, Clock::duration silence) {
  std::vector<std::string> gone;
  for (auto it = consumers_.begin(); it != consumers_.end();) {
    if (!it->second.own && wall - it->second.heard > silence) {
      gone.push_back(it->first);
      it = consumers_.erase(it);
      --programs_;
    } else {
      ++it;
    }
  }
  return gone;
}

void TruthDemand::reset() {
  for (auto& [name, c] : consumers_) {
    if (!c.own) c.instants.clear();
  }
  catch_up_ = false;
}

}  // namespace ubersim::physics
