#pragma once
// The demand book: which states physics publishes, as the union of what its
// consumers want (docs/sync.md, "Ground truth on demand"). Every reason to
// publish a step's state is a named consumer here: the programs that ask on
// SIM_TRUTH_DEMAND, and physics' own (--truth-every-step, the referee's state
// in sync mode, a STEP request, and what goes out while no program asks:
// every step or STATE_PUBLISH_RATE). A demanded instant is served by the
// first step at or after it (within a microsecond), as the vision emulator's
// capture schedule expects.
#include <chrono>
#include <cstdint>
#include <deque>
#include <limits>
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
  static constexpr int kMaxConsumers = 64;    // programs asking at once
  static constexpr int kMaxEntries = 256;     // periodic and explicit instants per consumer

  // When one of physics' own consumers counts.
  enum class While {
    Always,
    NobodyAsks,  // only while no program asks (physics' default publication)
  };

  // A program's whole demand; returns "" or why it was refused. `now` is
  // the sim time physics has reached: instants already passed are late.
  std::string on_demand(const truth_demand_t& demand, double now, double dt,
                        Clock::time_point wall);

  // Physics' own consumers: never forgotten for silence, not counted as a
  // program asking. Each call replaces what `name` wanted.
  void own_every_step(const std::string& name, While when);
  // Instants phase + n * period, n >= 0.
  void own_periodic(const std::string& name, double period, double phase, While when);
  // Every state at or after sim time `from` (up to `from` less a millionth of a step).
  void own_from(const std::string& name, double from);
  void forget(const std::string& name) { consumers_.erase(name); }

  // A state went out at sim time t (whatever the reason).
  void published(double t);
  // The one question: whether the state at the end of the step that went from
  // t - dt to t is wanted. Explicit instants it serves are used up.
  bool wanted(double t, double dt);
  // The same question, changing nothing: to see how far ahead the next wanted
  // state is (physics sleeps until its step is due; docs/sync.md).
  bool would_want(double t, double dt) const;
  // Forgets programs not heard for `silence`; returns their names.
  std::vector<std::string> expire(Clock::time_point wall, Clock::duration silence);
  // Sim time went back to 0: the programs' explicit instants of the old timeline go.
  void reset();

  // Programs asking (physics' own consumers not counted).
  std::size_t programs() const { return programs_; }
  std::uint64_t late() const { return late_; }

 private:
  struct Consumer {
    bool own = false;  // physics' own (never expires)
    While when = While::Always;
    bool every_step = false;
    std::vector<std::pair<double, double>> periodic;  // (period, phase)
    std::multiset<double> instants;
    double from = std::numeric_limits<double>::infinity();
    Clock::time_point heard{};
  };
  static bool periodic_due(const Consumer& c, double t, double dt);
  bool counts(const Consumer& c) const { return c.when == While::Always || programs_ == 0; }
  Consumer& own(const std::string& name, While when);

  std::map<std::string, Consumer> consumers_;
  std::size_t programs_ = 0;
  bool catch_up_ = false;  // a late instant: publish the next state
  // Recently published state times, to tell an instant already served (a
  // consumer repeating its demand) from one that came too late.
  std::deque<double> recent_;
  std::uint64_t late_ = 0;
};

}  // namespace ubersim::physics
