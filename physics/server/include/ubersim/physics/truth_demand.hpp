#pragma once
// Which states physics publishes with --truth-on-demand: the union of what the
// consumers asked for on SIM_TRUTH_DEMAND (docs/sync.md, "Ground truth on
// demand"). A demanded instant is served by the first step at or after it
// (within a microsecond), as the vision emulator's capture schedule expects.
#include <chrono>
#include <cstdint>
#include <deque>
#include <map>
#include <set>
#include <string>
#include <ubersim/truth_demand_t.hpp>
#include <vector>

namespace ubersim::physics {

class TruthDemand {
 public:
  using Clock = std::chrono::steady_clock;
  static constexpr double kTolerance = 1e-6;  // s
  static constexpr int kMaxConsumers = 64;
  static constexpr int kMaxEntries = 256;  // periodic and explicit instants per consumer

  // A consumer's whole demand; returns "" or why it was refused. `now` is
  // the sim time physics has reached: instants already passed are late.
  std::string on_demand(const truth_demand_t& demand, double now, double dt,
                        Clock::time_point wall);
  // A state went out at sim time t (whatever the reason).
  void published(double t);
  // Whether the state at the end of the step that went from t - dt to t is wanted.
  bool wanted(double t, double dt);
  // The same question, changing nothing: to see how far ahead the next wanted
  // state is (physics sleeps until its step is due; docs/sync.md).
  bool would_want(double t, double dt) const;
  // Forgets consumers not heard for `silence`; returns their names.
  std::vector<std::string> expire(Clock::time_point wall, Clock::duration silence);
  // Sim time went back to 0: explicit instants of the old timeline go.
  void reset();

  bool empty() const { return consumers_.empty(); }
  std::size_t consumers() const { return consumers_.size(); }
  std::uint64_t late() const { return late_; }

 private:
  struct Consumer {
    bool every_step = false;
    std::vector<std::pair<double, double>> periodic;  // (period, phase)
    std::multiset<double> instants;
    Clock::time_point heard{};
  };
  std::map<std::string, Consumer> consumers_;
  bool catch_up_ = false;  // a late instant: publish the next state
  // Recently published state times, to tell an instant already served (a
  // consumer repeating its demand) from one that came too late.
  std::deque<double> recent_;
  std::uint64_t late_ = 0;
};

}  // namespace ubersim::physics
