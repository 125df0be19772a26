#include "ubersim/radio/sync_coordinator.hpp"

#include <algorithm>
#include <ubersim/team_t.hpp>

namespace ubersim::radio {
namespace {

double seconds(SyncCoordinator::Clock::duration d) {
  return std::chrono::duration<double>(d).count();
}

}  // namespace

std::string SyncCoordinator::on_client(const sync_client_t& message) {
  if (message.team != team_t::YELLOW && message.team != team_t::BLUE) return "";
  const Team team = static_cast<Team>(message.team);
  Client& c = client(team);
  if (message.leaving) {
    if (!c.present || c.stats.name != message.name) return "";
    departed_.push_back(c.stats);
    c.present = false;
    c.owed.clear();
    return "sync client '" + message.name + "' (" + team_name(team) + ") left";
  }
  if (c.present) {
    if (c.stats.name == message.name) return "";  // the periodic repetition
    ++stats_.refused;
    return "sync client '" + message.name + "' refused: " + team_name(team) + " already has '" +
           c.stats.name + "' (one client per team)";
  }
  c.present = true;
  c.stats.name = message.name;
  c.stats.answers = c.stats.frames_skipped = 0;
  c.stats.answer_wall_seconds = c.stats.slowest_answer = 0;
  c.owed.clear();  // it answers frames published from now on
  return "sync client '" + message.name + "' registered for " + team_name(team);
}

void SyncCoordinator::on_schedule(const vision_schedule_t& schedule, Clock::time_point now) {
  if (schedule.step < 0) return;  // vision listens but has seen no state yet
  if (!(schedule.t_state >= 0) || !(schedule.next_publication >= schedule.t_state)) {
    ++stats_.schedules_out_of_order;  // not finite or not ahead: a bad message
    return;
  }
  const bool reset = schedule.step < last_schedule_step_;
  if (reset) {
    // Sim time went back: the world was reset; frames of the old one are owed no answer.
    for (Client& c : clients_) c.owed.clear();
  }
  // A schedule for a step already heard of (a repetition) announces no new frame.
  const bool fresh = reset || schedule.step > last_schedule_step_;
  ++stats_.schedules;
  vision_heard_ = true;
  last_schedule_step_ = schedule.step;
  last_schedule_time_ = schedule.t_state;
  next_publication_ = schedule.next_publication;
  const std::size_t frames =
      fresh ? std::min<std::size_t>(static_cast<std::size_t>(std::max(0, schedule.num_frames)),
                                    schedule.t_capture.size())
            : 0;
  stats_.frames += frames;
  for (Client& c : clients_) {
    if (!c.present) continue;
    for (std::size_t i = 0; i < frames; ++i) {
      c.owed.push_back({schedule.t_capture[i], schedule.t_state, now});
    }
  }
}

SyncCoordinator::Answer SyncCoordinator::on_answer(Team team, double t_sent,
                                                   Clock::time_point now) {
  Client& c = client(team);
  Answer answer;
  if (!c.present) {
    ++stats_.unregistered;
    answer.verdict = Verdict::Unregistered;
    return answer;
  }
  // The oldest owed frame with this capture time; frames before it were
  // skipped (the client answered a later one first): nothing to send for them.
  const auto match = std::find_if(c.owed.begin(), c.owed.end(),
                                  [&](const Outstanding& o) { return o.t_capture == t_sent; });
  if (match == c.owed.end()) {
    ++stats_.unmatched;
    answer.verdict = Verdict::Unmatched;
    return answer;
  }
  c.stats.frames_skipped += static_cast<std::uint64_t>(match - c.owed.begin());
  answer.verdict = Verdict::Accepted;
  answer.t_arrival = match->t_published;
  const double waited = seconds(now - match->wall_published);
  c.stats.answer_wall_seconds += waited;
  c.stats.slowest_answer = std::max(c.stats.slowest_answer, waited);
  ++c.stats.answers;
  ++stats_.answers;
  c.owed.erase(c.owed.begin(), match + 1);
  return answer;
}

std::vector<std::string> SyncCoordinator::expire(Clock::time_point now) {
  std::vector<std::string> dropped;
  for (Team team : kTeams) {
    Client& c = client(team);
    if (!c.present || c.owed.empty()) continue;
    const double waited = seconds(now - c.owed.front().wall_published);
    if (waited <= timeout_) continue;
    ++stats_.timeouts;
    dropped.push_back("'" + c.stats.name + "' (" + team_name(team) + ") did not answer the frame " +
                      "captured at " + std::to_string(c.owed.front().t_capture) + " s within " +
                      std::to_string(timeout_) + " s of wall time");
    departed_.push_back(c.stats);
    c.present = false;
    c.owed.clear();
  }
  return dropped;
}

double SyncCoordinator::earliest_arrival(Team team) const {
  const Client& c = client(team);
  if (!c.present || !vision_heard_) return kInfinity;
  if (!c.owed.empty()) return c.owed.front().t_published;
  return next_publication_;
}

std::string SyncCoordinator::bound_by(Team team) const {
  const Client& c = client(team);
  return c.present && !c.owed.empty() ? c.stats.name : std::string("vision");
}

int SyncCoordinator::clients() const {
  return static_cast<int>(clients_[0].present) + static_cast<int>(clients_[1].present);
}

std::optional<std::string> SyncCoordinator::client_name(Team team) const {
  const Client& c = client(team);
  if (!c.present) return std::nullopt;
  return c.stats.name;
}

std::vector<SyncClientStats> SyncCoordinator::client_stats() const {
  std::vector<SyncClientStats> all = departed_;
  for (const Client& c : clients_) {
    if (c.present) all.push_back(c.stats);
  }
  return all;
}

}  // namespace ubersim::radio
