#pragma once
// Sync mode through the SSL protocols (docs/sync.md, docs/ssl_bridge.md),
// for one team, without sockets: which detection frames the bridge forwarded
// to the team and which of them its RobotControl datagrams have answered.
//
// An SSL team cannot name the frame it answers (RobotControl has no time
// stamp), so the bridge relies on order: UDP on this host keeps it, and the
// team answers every detection packet with exactly one RobotControl, so each
// datagram answers the oldest forwarded frame not answered yet. A datagram
// when no frame is owed is the team's hello (the first one: it registers the
// team) or an extra one (counted and ignored).
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <deque>

namespace ubersim::ssl {

struct SyncAnswerStats {
  std::uint64_t frames = 0;     // detection frames owed an answer
  std::uint64_t answers = 0;    // datagrams that answered one
  std::uint64_t extra = 0;      // datagrams while nothing was owed (not the hello): ignored
  std::uint64_t timeouts = 0;   // times the team was dropped for answering too late
  std::uint64_t overflows = 0;  // times the team was dropped for owing too many frames
};

class SyncAnswers {
 public:
  using Clock = std::chrono::steady_clock;
  // More frames owed than this and the team is dropped: without sync physics
  // (or with a team that never answers) the queue would otherwise grow.
  static constexpr std::size_t kMaxOwed = 4096;

  explicit SyncAnswers(double timeout_s) : timeout_(timeout_s) {}

  bool registered() const { return registered_; }

  // A detection frame captured at t_capture went out to the team: owed an
  // answer if the team is registered. Returns true when the team was dropped
  // instead, owing kMaxOwed frames already.
  bool on_frame(double t_capture, Clock::time_point now);

  enum class Kind {
    Registered,  // the team's first datagram: it takes part from now on (not an answer)
    Answer,      // answers the frame captured at t_capture
    Extra,       // nothing was owed: ignored
  };
  struct Datagram {
    Kind kind = Kind::Extra;
    double t_capture = 0;  // s of sim time (Kind::Answer)
  };
  Datagram on_datagram();

  // Drops the team when its oldest owed frame has waited longer than the
  // timeout (wall time); true when it did. Its next datagram registers it again.
  bool expire(Clock::time_point now);

  // Forgets the frames owed and unregisters (the bridge says goodbye).
  void leave();

  std::size_t owed() const { return owed_.size(); }
  const SyncAnswerStats& stats() const { return stats_; }

 private:
  struct Owed {
    double t_capture;
    Clock::time_point sent;
  };
  double timeout_;
  bool registered_ = false;
  std::deque<Owed> owed_;
  SyncAnswerStats stats_;
};

}  // namespace ubersim::ssl
