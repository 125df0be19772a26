#pragma once
// Sync mode's bookkeeping (docs/sync.md), without LCM and without a clock (the
// wall time of each event is an argument): which control programs take part
// (SYNC_CLIENT), which frames were published and when (the frame schedule,
// SIM_VISION_SCHEDULE), and which of those each client has answered (its radio
// packets, t_sent = the frame's t_capture).
//
// An answer arrives, in sim time, when its frame was published: the client's
// own processing takes no sim time. So the earliest sim time a client's next
// answer can arrive is its oldest unanswered frame's publication, or, when it
// is up to date, the schedule's next publication. The radio links add their
// delay to that to give the simulation its horizon.
//
// A *timed* client (sync_client_t.timed: a team under the time shim) answers
// no frame: each packet's t_sent is the sim time it was sent (nondecreasing),
// and it arrives then; an empty packet at t_sent = c promises nothing before c
// (a null message). Its earliest next arrival is its latest t_sent.
#include <chrono>
#include <cstdint>
#include <deque>
#include <limits>
#include <optional>
#include <string>
#include <ubersim/sync_client_t.hpp>
#include <ubersim/sync_status_t.hpp>
#include <ubersim/vision_schedule_t.hpp>
#include <vector>

#include "ubersim/channels.hpp"

namespace ubersim::radio {

struct SyncClientStats {
  std::string name;
  std::uint64_t answers = 0;
  std::uint64_t frames_skipped = 0;  // answered a later frame first: these count as nothing to send
  double answer_wall_seconds = 0;    // sum over answers of wall time from publication to answer
  double slowest_answer = 0;         // s of wall time
};

struct SyncStats {
  std::uint64_t schedules = 0;
  std::uint64_t frames = 0;
  std::uint64_t answers = 0;
  std::uint64_t unregistered = 0;  // packets of a team with no registered client: ignored
  std::uint64_t unmatched = 0;     // duplicated, out of order, or for no published frame: ignored
  std::uint64_t timeouts = 0;      // clients dropped for answering too late
  std::uint64_t refused = 0;       // registrations for a team that already has a client
  std::uint64_t schedules_out_of_order = 0;
};

// What happened to one team's control (docs/sync.md, "A dropped client"): a
// team is without control from the sim time its client was dropped until a
// client registers for it again.
struct TeamControl {
  std::string client;          // its latest client's name (printable: it came off the wire)
  std::uint32_t drops = 0;     // times its client was dropped for answering too late
  double dropped_at = -1;      // s of sim time the current drop began; < 0: not dropped now
  double without_control = 0;  // s of sim time without control in drops that ended

  // s of sim time without control up to `now`, the current drop included.
  double without_control_until(double now) const;
};

// A client dropped by SyncCoordinator::expire.
struct Drop {
  Team team;
  std::string client;  // printable
  double t_sim;        // s of sim time: its first unanswered frame's publication
  double t_capture;    // that frame's capture time
  double timeout;      // s of wall time it had
  bool timed = false;  // a timed client: its promise (t_sim) stopped advancing

  // "sync client dropped: team yellow, client 'demo_yellow', at sim time ..." (one line,
  // the form tools/launch.sh and the batch runner read: docs/sync.md).
  std::string describe() const;
};

class SyncCoordinator {
 public:
  using Clock = std::chrono::steady_clock;
  static constexpr double kInfinity = std::numeric_limits<double>::infinity();

  explicit SyncCoordinator(double client_timeout_s) : timeout_(client_timeout_s) {}

  // Registration or goodbye; returns a line for the log when something changed.
  // A registration for a team whose client was dropped ends its time without
  // control ("sync client rejoined: ...").
  std::string on_client(const sync_client_t& message);
  void on_schedule(const vision_schedule_t& schedule, Clock::time_point now);

  enum class Verdict { Accepted, Unregistered, Unmatched };
  struct Answer {
    Verdict verdict = Verdict::Unmatched;
    double t_arrival = 0;  // s of sim time: when its frame was published
  };
  Answer on_answer(Team team, double t_sent, Clock::time_point now);

  // Drops every client whose oldest unanswered frame waits longer than the
  // timeout (the run goes on without it); returns them.
  std::vector<Drop> expire(Clock::time_point now);
  // The process keeping these books did not run for `gap` (a stalled process
  // or a paused machine): the clients could not answer in that time either, so it
  // does not count against their timeout.
  void forgive(Clock::duration gap);

  // The earliest sim time a further answer of `team` can arrive (kInfinity
  // when the team has no client, or no frame schedule was heard yet).
  double earliest_arrival(Team team) const;
  // Up to which sim time `team`'s answers are complete: its earliest arrival,
  // but for a timed client its promise only once it reached the next frame
  // (before, it may still send up to there: at most the latest schedule's
  // time), so that a run ends after everything it sends before that frame.
  double answered_until(Team team) const;
  // Who holds `team` back: its client's name when it owes an answer; nothing
  // when it waits for the schedule's next frame.
  std::optional<std::string> bound_by(Team team) const;

  bool schedule_heard() const { return schedule_heard_; }
  // Whether a timed client (a team program under the time shim) is registered.
  bool has_timed_client() const;
  bool timed(Team team) const;  // its client is a timed one
  int clients() const;
  std::optional<std::string> client_name(Team team) const;
  std::vector<SyncClientStats> client_stats() const;
  const SyncStats& stats() const { return stats_; }
  const TeamControl& control(Team team) const { return control_[static_cast<int>(team)]; }
  // s of sim time of the latest state the frame schedule announced (-inf before any).
  double sim_time() const { return last_schedule_time_; }
  // The teams' control as SIM_SYNC_STATUS says it (sequence not set).
  sync_status_t status() const;
  // "sync: no client was dropped" or "sync: degraded run: ..." (until the latest sim time).
  std::string summary() const;

 private:
  struct Outstanding {
    double t_capture;
    double t_published;
    Clock::time_point wall_published;
  };
  struct Client {
    bool present = false;
    SyncClientStats stats;
    std::deque<Outstanding> owed;
    // Timed clients: the latest t_sent (its promise), and since when (wall
    // time) it lags behind the next frame's publication without advancing.
    bool timed = false;
    double promise = 0;
    bool behind = false;
    Clock::time_point behind_since{};
  };
  Answer on_timed_answer(Client& c, double t_sent, Clock::time_point now);
  void note_progress(Client& c, Clock::time_point now) const;
  bool reached_next_frame(const Client& c) const;
  Client& client(Team team) { return clients_[static_cast<int>(team)]; }
  const Client& client(Team team) const { return clients_[static_cast<int>(team)]; }

  double timeout_;
  Client clients_[2];
  bool schedule_heard_ = false;
  double next_publication_ = 0;
  double last_schedule_time_ = -kInfinity;
  std::int64_t last_schedule_step_ = -1;
  SyncStats stats_;
  TeamControl control_[2];
  std::vector<SyncClientStats> departed_;
};

}  // namespace ubersim::radio
