#pragma once
// One team's feedback (return) channel, in sim time. At FEEDBACK_RATE the
// robots' reports (ball on the dribbler, kicker charged) are sampled from the
// ground truth; each packet may be lost whole, each robot's report may be lost
// on its own, and what gets through reaches the team's control software
// FEEDBACK_LATENCY (+ jitter, order kept) later.
//
// Unlike commands (which physics holds until t_apply), feedback is published by
// this emulator itself, on the first SIM_STATE at or after its delivery time;
// t_sent is the delivery time, t_measured + latency (+ jitter).
#include <cstdint>
#include <ubersim/radio_feedback_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <vector>

#include "ubersim/delay_line.hpp"
#include "ubersim/radio/link_random.hpp"
#include "ubersim/radio/radio_profile.hpp"

namespace ubersim::radio {

struct FeedbackLinkStats {
  std::uint64_t sampled = 0;       // packets the robots sent
  std::uint64_t lost_packets = 0;  // lost whole
  std::uint64_t lost_reports = 0;  // single robot reports lost
  std::uint64_t delivered = 0;     // packets published to the team
};

class FeedbackLink {
 public:
  static constexpr double kTimeEpsilon = kReleaseEpsilon;  // s

  FeedbackLink(const RadioProfile& profile, Team team, std::uint64_t seed);

  // Called with every accepted SIM_STATE (its time is `state.sim_time`): samples
  // the team's robots when a feedback period is due, and returns every packet
  // whose delivery time has come, oldest first, with t_sent set.
  std::vector<radio_feedback_t> on_sim_state(const sim_state_t& state);
  void reset();
  // New delay and loss from the next sample on (a run-time realism change).
  void set_profile(const RadioProfile& profile) { profile_ = profile; }

  const FeedbackLinkStats& stats() const { return stats_; }
  // Sim time of the first sample of the current sampling grid (0 before the
  // first state); samples follow at 1 / FEEDBACK_RATE, so physics on demand is
  // asked for states at those instants. The grid's origin, not the next
  // sample: it stays the same from sample to sample, and so does the demand.
  double sample_phase() const;
  double rate() const { return profile_.feedback_rate; }
  // The earliest sim time whose state this link still has to see: its next
  // sample or its oldest packet's delivery; 0 before the first state, +inf
  // with no feedback (FEEDBACK_RATE 0).
  double next_due() const;
  // Delivery times of the packets on their way, oldest first.
  std::vector<double> release_times() const { return in_flight_.release_times(); }

 private:
  void sample(const sim_state_t& state);

  RadioProfile profile_;
  Team team_;
  LinkRandom random_;
  double next_sample_;
  double grid_origin_ = 0;  // s, the first sample since the grid (re)started
  DelayLine<radio_feedback_t> in_flight_;
  FeedbackLinkStats stats_;
};

}  // namespace ubersim::radio
