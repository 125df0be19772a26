#pragma once
// The radio emulator without its transport: both teams' links, fed with
// SIM_STATE and radio packets; each call returns what gets through. The
// program (main.cpp) wires it to LCM; tests can drive it in-process. The same
// shape as the physics and vision cores (docs/design.md, "One shape for the
// cores").
//
// Sim time of a packet's arrival is the time of the latest SIM_STATE seen, so
// with physics paced in real time the arrival time has a granularity of one
// physics step (4.2 ms at 240 Hz). The core reads no clock: the wall time a
// state or packet came at is an argument (the process host's clock).
#include <array>
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <ubersim/emulator_realism_t.hpp>
#include <ubersim/radio_feedback_t.hpp>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/sim_commands_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <ubersim/truth_demand_t.hpp>
#include <utility>
#include <vector>

#include "ubersim/logging.hpp"
#include "ubersim/radio/command_link.hpp"
#include "ubersim/radio/command_validator.hpp"
#include "ubersim/radio/feedback_link.hpp"
#include "ubersim/radio/radio_profile.hpp"
#include "ubersim/sim_clock.hpp"

namespace ubersim::radio {

struct TeamReport {
  std::uint64_t packets_received = 0;
  std::array<std::uint64_t, kProblemCount> problems{};  // by Problem
  CommandLinkStats commands;
  FeedbackLinkStats feedback;

  std::uint64_t problem(Problem p) const { return problems[static_cast<int>(p)]; }
};

class RadioEmulator {
 public:
  using Clock = std::chrono::steady_clock;

  // What one call produced, to publish in this order.
  struct Output {
    std::vector<sim_commands_t> commands;                     // SIM_COMMANDS
    std::vector<std::pair<Team, radio_feedback_t>> feedback;  // RADIO_FEEDBACK_<team>
  };

  // seed_override replaces both profiles' SEED (the --seed option).
  RadioEmulator(const std::array<RadioProfile, 2>& profiles,
                std::optional<std::uint64_t> seed_override);

  // `wall`: when the state came (paced modes place packets between states by it).
  Output on_sim_state(const sim_state_t& state, Clock::time_point wall);
  // A packet that came on `channel_team`'s radio channel at `wall`.
  Output on_radio_packet(Team channel_team, const radio_packet_t& packet, Clock::time_point wall);

  // Sync mode (docs/sync.md): packets arrive at the sim time given (their
  // frame's publication), not at the latest SIM_STATE's, and a waiting packet
  // goes out only when sync_poll() says no newer one can arrive before the
  // link frees; SIM_STATE then only drives the feedback.
  void set_sync(bool sync) { sync_ = sync; }
  Output on_answer(Team channel_team, const radio_packet_t& packet, double t_arrival);
  // Whether a SIM_STATE came: until then which robots are on the field is
  // unknown, and an answer cannot be checked against them.
  bool has_sim_time() const { return clock_.started(); }
  // What a sync driver does between answers (the radio emulator's SyncDriver,
  // the Python module's InProcessSim; docs/sync.md): no packet of `team` can
  // arrive before `earliest_arrival` (s of sim time), so what its link
  // transmits before then goes out (`out`, for physics), and physics may start
  // every step before `horizon`: the earliest t_apply a command of `team` not
  // yet forwarded can still get.
  struct SyncRelease {
    Output out;
    double horizon = 0;
  };
  SyncRelease sync_release(Team team, double earliest_arrival);
  // Sync mode with a timed client (docs/sync.md, "Timed clients"): its team
  // program gets the feedback at the sim time it was sent, so physics must
  // not pass a state the feedback links still have to see (a sample, a
  // delivery) before this emulator saw it: feedback_due() bounds the horizon,
  // and the truth demand names the deliveries too, so that physics publishes
  // the state it waits at.
  void set_feedback_in_step(bool in_step) { feedback_in_step_ = in_step; }
  bool feedback_in_step() const { return feedback_in_step_; }
  double feedback_due() const;

  // A run-time realism change (EMULATOR_REALISM) for both teams: the radio
  // values >= 0 replace the profiles'. Returns what was wrong (nothing
  // applied), or "".
  std::string apply_realism(const emulator_realism_t& realism);
  const RadioProfile& profile(Team team) const { return link(team).profile; }

  // The ground truth this emulator needs (SIM_TRUTH_DEMAND): each team's
  // feedback samples and, outside sync mode, the moment a waiting packet's
  // link frees (sync mode transmits it without a state).
  truth_demand_t truth_demand() const;

  TeamReport report(Team team) const;
  std::string summary(Team team) const;  // one line for the log
  std::uint64_t rejected_sim_states() const { return rejected_sim_states_; }
  std::uint64_t resets() const { return resets_; }
  ThrottledLog& warnings() { return warnings_; }

 private:
  struct TeamLink {
    TeamLink(const RadioProfile& team_profile, Team team, std::uint64_t seed)
        : profile(team_profile),
          commands(team_profile, team, seed),
          feedback(team_profile, team, seed) {}
    RadioProfile profile;
    CommandLink commands;
    FeedbackLink feedback;
    RobotsOnField robots;
    std::uint64_t packets_received = 0;
    std::array<std::uint64_t, kProblemCount> problems{};
  };

  // What the link of `team` transmits before `earliest_arrival`.
  Output sync_poll(Team team, double earliest_arrival);
  TeamLink& link(Team team) { return links_[static_cast<int>(team)]; }
  const TeamLink& link(Team team) const { return links_[static_cast<int>(team)]; }
  void record(Team team, const Finding& finding);
  static void add(Output& out, std::optional<sim_commands_t> message);

  std::array<TeamLink, 2> links_;
  SimClock clock_;
  ThrottledLog warnings_;
  std::uint64_t rejected_sim_states_ = 0;
  std::uint64_t resets_ = 0;
  bool sync_ = false;
  bool feedback_in_step_ = false;
  // Physics may publish only some states (on demand): between two, a packet's
  // arrival is the last state's time plus the wall time since, times the speed
  // (paced modes only; as fast as possible there is no better guess).
  double arrival_time(Clock::time_point wall) const;
  Clock::time_point last_state_wall_{};
  double speed_factor_ = 0;
  double step_ = 1;  // s, physics' dt
};

}  // namespace ubersim::radio
