#pragma once
// The link between ubersim's sync mode and the official ssl-game-controller in
// CI mode, as a pure core: no LCM, no socket, no clock. For each ground-truth
// state physics stops at it decides whether the GC must be asked (its tick
// period is up, a detector saw a game event, the operator has something to
// do) and which conversation to hold (CiConversation); from the GC's settled
// Referee it makes what goes out: REFEREE (referee_t in sim time, naming the
// state to stop at next), the field placement the GC needs (FieldKeeper),
// event-log lines. The program around it (link_runner) moves the bytes.
#include <functional>
#include <optional>
#include <string>
#include <ubersim/field_geometry_t.hpp>
#include <ubersim/referee_t.hpp>
#include <ubersim/sim_control_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <vector>

#include "ubersim/gc_link/ci_conversation.hpp"
#include "ubersim/gc_link/field_keeper.hpp"
#include "ubersim/gc_link/gc_inputs.hpp"
#include "ubersim/referee/autoref.hpp"
#include "ubersim/ssl_bridge/official_referee.hpp"
#include "ubersim/ssl_bridge/tracked_frames.hpp"

namespace ubersim::gc_link {

struct LinkOptions {
  GameSetup setup;
  // The built-in referee's rules, used for its detectors only (goals, outs,
  // the fouls it knows); its clocks are made never to end a half.
  referee::GameConfig detectors;
  double tick_period = 0.025;  // s of sim time between GC ticks (the GC ticks at 40 Hz itself)
};

// What one state makes the link send.
struct LinkOutput {
  bool judged = false;
  std::optional<sim_control_t> placement;  // SIM_CONTROL PLACE (request_id, sender unset)
  std::optional<referee_t> referee;        // REFEREE
  std::vector<std::string> log_lines;      // event log (JSON lines)
  bool game_over = false;                  // the GC reached POST_GAME just now
};

class GcLink {
 public:
  GcLink(LinkOptions options, field_geometry_t field,
         std::function<double(const std::string&)> radius_of);

  // A state arrived: the conversation to hold with the GC before finish(), or
  // nothing (no tick due, or a state not judged).
  std::optional<CiConversation> begin(const sim_state_t& state);
  // After the conversation (nullptr: none was needed): what goes out.
  LinkOutput finish(const sim_state_t& state, const CiConversation* conversation);

  void set_field(const field_geometry_t& field);

  const Referee& gc() const { return gc_; }
  std::uint64_t ticks() const { return ticks_; }
  std::uint64_t judged() const { return judged_; }
  std::uint64_t refused() const { return refused_; }
  std::uint64_t reports() const { return reports_; }
  double last_time() const { return last_time_; }
  // The result line of the event log, from the GC's last Referee.
  std::string result_line(double wall_time) const;

 private:
  bool judges(const sim_state_t& state) const;
  std::vector<Input> reports_for(const referee::Decision& decision);
  CiInput tick_input(const sim_state_t& state);
  std::optional<sim_control_t> place(const referee::SituationRequest& request,
                                     const sim_state_t& state) const;
  void log_changes(const sim_state_t& state, LinkOutput& out);

  LinkOptions options_;
  field_geometry_t field_;
  std::function<double(const std::string&)> radius_of_;
  referee::AutoReferee detectors_;
  ssl::TrackedFrames frames_;
  ssl::OfficialRefereeTracker translation_;
  Operator operator_;
  FieldKeeper keeper_;
  Referee gc_;  // the GC's last settled Referee
  std::uint64_t barriers_ = 0;
  bool geometry_due_ = true;
  bool in_conversation_ = false;
  bool over_ = false;
  double next_tick_ = 0;    // s
  double next_detect_ = 0;  // s, the state the detectors name next
  double next_judge_ = 0;   // s, the state the link judges next
  double last_time_ = 0;    // s
  bool judged_any_ = false;
  std::uint64_t ticks_ = 0, judged_ = 0, refused_ = 0, reports_ = 0;
  std::optional<std::uint32_t> logged_counter_;
  int logged_events_ = 0;
  std::uint32_t logged_yellow_ = 0, logged_blue_ = 0;
};

// The built-in referee's rules as detectors under the GC: the halves and its
// restart clocks never hold a detection back longer than they must.
referee::GameConfig detector_config(referee::GameConfig rules);

}  // namespace ubersim::gc_link
