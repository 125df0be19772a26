#include "ubersim/radio/radio_emulator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <ubersim/team_t.hpp>

#include "ubersim/spdlog.hpp"

namespace ubersim::radio {
namespace {

std::uint64_t seed_of(const RadioProfile& profile, std::optional<std::uint64_t> seed_override) {
  return seed_override ? *seed_override : profile.seed;
}

}  // namespace

RadioEmulator::RadioEmulator(const std::array<RadioProfile, 2>& profiles,
                             std::optional<std::uint64_t> seed_override)
    : links_{TeamLink(profiles[0], Team::Yellow, seed_of(profiles[0], seed_override)),
             TeamLink(profiles[1], Team::Blue, seed_of(profiles[1], seed_override))} {}

RadioEmulator::Output RadioEmulator::on_sim_state(const sim_state_t& state,
                                                  Clock::time_point wall) {
  Output out;
  switch (clock_.update(state.sim_time, state.step)) {
    case SimClock::Update::Rejected:
      ++rejected_sim_states_;
      warnings_.warn("sim_state",
                     "ignored a SIM_STATE that goes back in time or is not finite (t=" +
                         std::to_string(state.sim_time) + " s)");
      return out;
    case SimClock::Update::Reset:
      ++resets_;
      spdlog::info("sim time went back to {:.3f} s: world reset, radio links start afresh",
                   state.sim_time);
      for (auto& team_link : links_) {
        team_link.commands.reset();
        team_link.feedback.reset();
      }
      break;
    case SimClock::Update::Advanced:
      break;
  }

  last_state_wall_ = wall;
  speed_factor_ = state.paused || !(state.dt > 0) ? 0.0 : state.speed_factor;
  step_ = state.dt;
  for (auto& team_link : links_) team_link.robots.clear();
  for (const auto& robot : state.robots) {
    if (robot.team != team_t::YELLOW && robot.team != team_t::BLUE) continue;
    links_[robot.team].robots[robot.robot_id] = robot.num_wheels;
  }

  for (Team team : kTeams) {
    TeamLink& team_link = link(team);
    if (!sync_) add(out, team_link.commands.poll(clock_.now()));
    for (auto& feedback : team_link.feedback.on_sim_state(state)) {
      out.feedback.emplace_back(team, std::move(feedback));
    }
  }
  return out;
}

RadioEmulator::Output RadioEmulator::on_radio_packet(Team channel_team,
                                                     const radio_packet_t& packet,
                                                     Clock::time_point wall) {
  Output out;
  TeamLink& team_link = link(channel_team);
  ++team_link.packets_received;
  if (!clock_.started()) {
    record(channel_team, {Problem::NoSimTime, -1, "no SIM_STATE yet: the sim time is unknown"});
    return out;
  }
  Validated validated =
      validate_packet(packet, channel_team, team_link.profile.limits, team_link.robots);
  for (const auto& finding : validated.findings) record(channel_team, finding);
  if (!validated.packet_ok || validated.packet.commands.empty()) return out;
  add(out, team_link.commands.offer(std::move(validated.packet), arrival_time(wall)));
  return out;
}

double RadioEmulator::arrival_time(Clock::time_point wall) const {
  if (speed_factor_ <= 0) return clock_.now();
  const double since_state = std::chrono::duration<double>(wall - last_state_wall_).count();
  // In whole physics steps, as with a state every step (so the same packets
  // get the same stamps whichever states physics sends); at most 0.1 s: beyond
  // that physics has stopped or fell behind.
  const double steps = std::floor(since_state * speed_factor_ / step_);
  return clock_.now() + std::min(0.1, steps * step_);
}

RadioEmulator::Output RadioEmulator::on_answer(Team channel_team, const radio_packet_t& packet,
                                               double t_arrival) {
  TeamLink& team_link = link(channel_team);
  ++team_link.packets_received;
  Output out = sync_poll(channel_team, t_arrival);
  if (packet.num_commands == 0 && packet.commands.empty()) return out;  // "nothing to send"
  Validated validated =
      validate_packet(packet, channel_team, team_link.profile.limits, team_link.robots);
  for (const auto& finding : validated.findings) record(channel_team, finding);
  if (!validated.packet_ok || validated.packet.commands.empty()) return out;
  add(out, team_link.commands.offer(std::move(validated.packet), t_arrival));
  return out;
}

RadioEmulator::SyncRelease RadioEmulator::sync_release(Team team, double earliest_arrival) {
  SyncRelease release;
  release.out = sync_poll(team, earliest_arrival);
  release.horizon = link(team).commands.earliest_apply(earliest_arrival);
  return release;
}

double RadioEmulator::feedback_due() const {
  double due = std::numeric_limits<double>::infinity();
  for (const auto& team_link : links_) due = std::min(due, team_link.feedback.next_due());
  return due;
}

RadioEmulator::Output RadioEmulator::sync_poll(Team team, double earliest_arrival) {
  // A packet arriving exactly when the link frees replaces the waiting one,
  // so transmit only what frees strictly before the next possible arrival.
  Output out;
  add(out, link(team).commands.poll(earliest_arrival - 2 * CommandLink::kTimeEpsilon));
  return out;
}

void RadioEmulator::add(Output& out, std::optional<sim_commands_t> message) {
  if (message) out.commands.push_back(std::move(*message));
}

void RadioEmulator::record(Team team, const Finding& finding) {
  ++link(team).problems[static_cast<int>(finding.problem)];
  std::string message =
      std::string("dropped from ") + team_name(team) + " radio: " + problem_name(finding.problem);
  if (finding.robot_id >= 0) message += " (robot " + std::to_string(finding.robot_id) + ")";
  if (!finding.detail.empty()) message += ": " + finding.detail;
  warnings_.warn(std::string(team_name(team)) + ":" + problem_name(finding.problem), message);
}

truth_demand_t RadioEmulator::truth_demand() const {
  truth_demand_t demand{};
  demand.consumer = "radio";
  for (const auto& team_link : links_) {
    if (team_link.feedback.rate() > 0) {
      demand.period.push_back(1.0 / team_link.feedback.rate());
      demand.phase.push_back(team_link.feedback.sample_phase());
    }
    if (!sync_ && team_link.commands.has_waiting_packet()) {
      demand.instants.push_back(team_link.commands.busy_until());
    }
    if (feedback_in_step_) {
      for (double release : team_link.feedback.release_times()) demand.instants.push_back(release);
    }
  }
  demand.num_periodic = static_cast<std::int32_t>(demand.period.size());
  demand.num_instants = static_cast<std::int32_t>(demand.instants.size());
  return demand;
}

TeamReport RadioEmulator::report(Team team) const {
  const TeamLink& team_link = link(team);
  TeamReport r;
  r.packets_received = team_link.packets_received;
  r.problems = team_link.problems;
  r.commands = team_link.commands.stats();
  r.feedback = team_link.feedback.stats();
  return r;
}

std::string RadioEmulator::summary(Team team) const {
  const TeamReport r = report(team);
  std::string text =
      std::string(team_name(team)) + " (profile " + link(team).profile.name + "): received " +
      std::to_string(r.packets_received) + ", superseded " + std::to_string(r.commands.superseded) +
      ", transmitted " + std::to_string(r.commands.transmitted) + ", lost " +
      std::to_string(r.commands.lost_packets) + " packets + " +
      std::to_string(r.commands.lost_entries) + " robot entries, forwarded " +
      std::to_string(r.commands.forwarded_packets) + "; feedback sent " +
      std::to_string(r.feedback.sampled) + ", lost " + std::to_string(r.feedback.lost_packets) +
      ", delivered " + std::to_string(r.feedback.delivered);
  for (int p = 0; p < kProblemCount; ++p) {
    if (r.problems[p] == 0) continue;
    text += "; " + std::string(problem_name(static_cast<Problem>(p))) + ": " +
            std::to_string(r.problems[p]);
  }
  return text;
}

}  // namespace ubersim::radio
