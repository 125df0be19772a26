#pragma once
// What ubersim tells the official game controller, as CiInput parts: the game's
// set-up, the field, ground truth as a tracker frame, the game events the
// built-in automatic referee's detectors saw (as an autoref reports them), and
// the few things a human operator does at the GC (start the game, resume
// after a HALT, end halves and the break). Pure: protobuf in, protobuf out.
#include <ssl_gc_ci.pb.h>

#include <optional>
#include <string>
#include <ubersim/field_geometry_t.hpp>
#include <vector>

#include "ubersim/referee/autoref.hpp"

namespace ubersim::gc_link {

// The origin our game events carry: an autoref of that name (registered with
// the GC by setup_inputs so that its proposals count).
inline constexpr const char* kAutoRefName = "ubersim";

struct GameSetup {
  std::string yellow_name = "Yellow";
  std::string blue_name = "Blue";
  int yellow_keeper = 0;
  int blue_keeper = 0;
  bool division_a = false;
  ubersim::Team first_kickoff = ubersim::Team::Yellow;
  referee::FieldSides sides;
};

// The first exchange's inputs: a fresh match (reset), ubersim as an autoref
// whose reports are accepted, auto-continue on, division, first kick-off,
// a friendly match, and per team its name, keeper, side and that it cannot
// place the ball (no team places it in simulation: ubersim does, FieldKeeper).
std::vector<Input> setup_inputs(const GameSetup& setup);

// The field as the SSL-Vision geometry packet gives it (mm).
SSL_GeometryData geometry_data(const field_geometry_t& field);

// One game event of the built-in referee as an autoref reports it, or nothing
// for the events the GC judges itself (no progress, too many robots).
// A goal is reported as POSSIBLE_GOAL: the GC checks and approves it.
std::optional<Input> report(const referee::GameEvent& event);

// Whether the GC takes reports of fouls and outs now: the ball is in play or
// a restart is being taken (after NORMAL_START, FORCE_START, DIRECT_FREE_*).
bool reports_wanted(const Referee& gc);

// A change of the command / stage, as the operator gives it.
Input command_input(Command::Type type, ::Team team = ::UNKNOWN);
Input stage_input(Referee::Stage stage);

// The operator's part, for an unattended game: what a human at the GC would
// do now, given its last Referee and the sim time. Remembers when the GC
// entered HALT (resume after kHaltHold).
class Operator {
 public:
  static constexpr double kHaltHold = 0.5;  // s of HALT before STOP (the ball is placed meanwhile)

  std::vector<Input> decide(const Referee& gc, double sim_time);
  bool started() const { return started_; }

 private:
  bool started_ = false;
  std::optional<std::uint32_t> halt_counter_;  // command_counter of the HALT being held
  double halt_since_ = 0;                      // s
};

}  // namespace ubersim::gc_link
