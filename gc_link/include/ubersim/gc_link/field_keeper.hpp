#pragma once
// What the official game controller asks of the field and no team does in
// simulation, done the way ssl-simulation-controller does it
// (internal/simctl/handler_replace_ball.go at 1c98577): once the GC has held
// a stoppage for kHold, a ball that lies more than kTolerance from the
// designated position is put there (robots in the way step aside), at most
// every kHold. ubersim's teams place no ball, so it does this in STOP as well
// as in HALT. For a kick-off or a penalty the robots are put where the rules
// want them too (our demo team holds where it is placed during PREPARE_*),
// when the stop before it has been held for kHold and again when the
// PREPARE_* command comes. Pure: the GC's Referee and the state in, the
// situation to set up out.
#include <ssl_gc_referee_message.pb.h>

#include <cstdint>
#include <optional>
#include <ubersim/sim_state_t.hpp>

#include "ubersim/referee/situations.hpp"

namespace ubersim::gc_link {

class FieldKeeper {
 public:
  static constexpr double kHold = 0.5;       // s, as ssl-simulation-controller waits
  static constexpr double kTolerance = 0.1;  // m, as ssl-simulation-controller tolerates

  std::optional<referee::SituationRequest> decide(const Referee& gc, const sim_state_t& state);

 private:
  std::optional<std::uint32_t> counter_;   // command_counter of the command being held
  double since_ = 0;                       // s, when it came
  double last_placed_ = -1e9;              // s
  std::optional<std::uint32_t> prepared_;  // command_counter of the PREPARE_* already set up
};

}  // namespace ubersim::gc_link
