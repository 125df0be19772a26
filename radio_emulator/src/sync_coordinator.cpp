#include "ubersim/radio/sync_coordinator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <iterator>
#include <ubersim/team_t.hpp>

namespace ubersim::radio {
namespace {

double seconds(SyncCoordinator::Clock::duration d) {
  return std::chrono::duration<double>(d).count();
}

// A client's name as the log lines that tools read can carry it: it came off
// the wire, so no line break, no quote, at most 64 characters.
std::string printable(const std::string& name) {
  std::string out = name.substr(0, 64);
  for (char& c : out) {
    if (c < 0x20 || c > 0x7e || c == '\'' || c == '\\') c = '?';
  }
  return out;
}

}  // namespace

double TeamControl::without_control_until(double now) const {
  return without_control + (dropped_at >= 0 ? std::max(0.0, now - dropped_at) : 0.0);
}

std::string Drop::describe() const {
  if (timed) {
    return fmt::format(
        "sync client dropped: team {}, client '{}', at sim time {:.3f} s: its time did not "
        "advance past that (no packet, no promise) within {:g} s of wall time while the "
        "simulation waited for it; the {} team is without control until a client registers "
        "for it again",
        team_name(team), client, t_sim, timeout, team_name(team));
  }
  return fmt::format(
      "sync client dropped: team {}, client '{}', at sim time {:.3f} s: it did not answer the "
      "frame captured at {:.3f} s within {:g} s of wall time; the {} team is without control "
      "until a client registers for it again",
      team_name(team), client, t_sim, t_capture, timeout, team_name(team));
}

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
  TeamControl& control = control_[static_cast<int>(team)];
  std::string rejoined;
  if (control.dropped_at >= 0) {
    // Control is back from the next frame on: its answers count from now.
    const double now = std::max(last_schedule_time_, control.dropped_at);
    const double lost = now - control.dropped_at;
    control.without_control += lost;
    control.dropped_at = -1;
    rejoined = fmt::format(
        "sync client rejoined: team {}, client '{}', at sim time {:.3f} s, after {:.3f} s of sim "
        "time without control",
        team_name(team), printable(message.name), now, lost);
  }
  control.client = printable(message.name);
  c.present = true;
  c.stats.name = message.name;
  c.stats.answers = c.stats.frames_skipped = 0;
  c.stats.answer_wall_seconds = c.stats.slowest_answer = 0;
  c.owed.clear();  // it answers frames published from now on
  c.timed = message.timed;
  c.promise = 0;
  c.behind = false;
  if (!rejoined.empty()) return rejoined;
  return "sync client '" + message.name + "' registered for " + team_name(team);
}

void SyncCoordinator::on_schedule(const vision_schedule_t& schedule, Clock::time_point now) {
  if (schedule.step < 0) return;  // its sender listens but has seen no state yet
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
  schedule_heard_ = true;
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
    if (c.timed) {
      note_progress(c, now);
      continue;  // it answers no frame
    }
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
  if (c.timed) return on_timed_answer(c, t_sent, now);
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

SyncCoordinator::Answer SyncCoordinator::on_timed_answer(Client& c, double t_sent,
                                                         Clock::time_point now) {
  Answer answer;
  if (!(t_sent >= c.promise) || !(t_sent < 1e9)) {
    ++stats_.unmatched;  // earlier than it promised, or not a time: out of order
    return answer;
  }
  const bool advanced = t_sent > c.promise;
  c.promise = t_sent;
  answer.verdict = Verdict::Accepted;
  answer.t_arrival = t_sent;
  ++c.stats.answers;
  ++stats_.answers;
  if (advanced) c.behind = false;
  note_progress(c, now);
  return answer;
}

// A timed client lags when its promise is short of the next frame's
// publication: the simulation cannot pass it until the promise advances.
void SyncCoordinator::note_progress(Client& c, Clock::time_point now) const {
  const bool lags = schedule_heard_ && !reached_next_frame(c);
  if (lags && !c.behind) c.behind_since = now;
  c.behind = lags;
}

// A timed client's clock counts whole nanoseconds: its promise of the next
// frame's publication may fall short of the schedule's double by less than one.
bool SyncCoordinator::reached_next_frame(const Client& c) const {
  constexpr double kClockResolution = 1e-9;  // s
  return c.promise >= next_publication_ - kClockResolution;
}

std::vector<Drop> SyncCoordinator::expire(Clock::time_point now) {
  std::vector<Drop> dropped;
  for (Team team : kTeams) {
    Client& c = client(team);
    if (c.present && c.timed) {
      if (!c.behind || seconds(now - c.behind_since) <= timeout_) continue;
      ++stats_.timeouts;
      TeamControl& control = control_[static_cast<int>(team)];
      ++control.drops;
      control.dropped_at = c.promise;
      dropped.push_back({team, control.client, c.promise, c.promise, timeout_, true});
      departed_.push_back(c.stats);
      c.present = false;
      continue;
    }
    if (!c.present || c.owed.empty()) continue;
    const Outstanding& oldest = c.owed.front();
    if (seconds(now - oldest.wall_published) <= timeout_) continue;
    ++stats_.timeouts;
    TeamControl& control = control_[static_cast<int>(team)];
    ++control.drops;
    // Its answers stop with this frame: the team is without control from its publication.
    control.dropped_at = oldest.t_published;
    dropped.push_back({team, control.client, oldest.t_published, oldest.t_capture, timeout_});
    departed_.push_back(c.stats);
    c.present = false;
    c.owed.clear();
  }
  return dropped;
}

void SyncCoordinator::forgive(Clock::duration gap) {
  for (Client& c : clients_) {
    for (Outstanding& o : c.owed) o.wall_published += gap;
    c.behind_since += gap;
  }
}

sync_status_t SyncCoordinator::status() const {
  sync_status_t status{};
  status.t = std::max(0.0, last_schedule_time_);
  for (Team team : kTeams) {
    const int i = static_cast<int>(team);
    status.client[i] = control_[i].client;
    status.drops[i] = static_cast<std::int32_t>(control_[i].drops);
    status.dropped_at[i] = control_[i].dropped_at;
    status.without_control[i] = control_[i].without_control;
  }
  return status;
}

std::string SyncCoordinator::summary() const {
  const double now = std::max(0.0, last_schedule_time_);
  std::vector<std::string> teams;
  for (Team team : kTeams) {
    const TeamControl& control = control_[static_cast<int>(team)];
    if (control.drops == 0) continue;
    teams.push_back(fmt::format(
        "{} without control for {:.3f} s of sim time ({} drop{} of client '{}'{})", team_name(team),
        control.without_control_until(now), control.drops, control.drops == 1 ? "" : "s",
        control.client, control.dropped_at >= 0 ? ", not back by the end" : ", back by the end"));
  }
  if (teams.empty()) return "sync: no client was dropped";
  std::string joined;
  for (const std::string& team : teams) joined += (joined.empty() ? "" : "; ") + team;
  return fmt::format("sync: degraded run: {} (of {:.3f} s of sim time)", joined, now);
}

double SyncCoordinator::earliest_arrival(Team team) const {
  const Client& c = client(team);
  if (!c.present || !schedule_heard_) return kInfinity;
  if (c.timed) return c.promise;
  if (!c.owed.empty()) return c.owed.front().t_published;
  return next_publication_;
}

double SyncCoordinator::answered_until(Team team) const {
  const Client& c = client(team);
  const double arrival = earliest_arrival(team);
  if (!c.present || !c.timed || reached_next_frame(c)) return arrival;
  return std::min(c.promise, last_schedule_time_);
}

std::optional<std::string> SyncCoordinator::bound_by(Team team) const {
  const Client& c = client(team);
  if (c.present && (c.timed ? c.behind : !c.owed.empty())) return c.stats.name;
  return std::nullopt;
}

bool SyncCoordinator::has_timed_client() const {
  return std::any_of(std::begin(clients_), std::end(clients_),
                     [](const Client& c) { return c.present && c.timed; });
}

bool SyncCoordinator::timed(Team team) const {
  const Client& c = client(team);
  return c.present && c.timed;
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
