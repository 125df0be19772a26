#pragma once
// How the demo team obeys the referee (referee_t on REFEREE): HALT stands
// still, STOP keeps 0.6 m from the ball at 1 m/s, a kick-off or penalty being
// prepared is held where the referee placed everyone, and a restart belongs to
// the team it names until the ball is in play; the other team waits for it.
// Without any referee message the team just plays.
#include <deque>
#include <optional>
#include <ubersim/referee_t.hpp>
#include <ubersim/robot_command_t.hpp>
#include <vector>

#include "behaviour.hpp"

namespace demo {

enum class GameMode { Play, Halt, Stop, Hold };

class RefereeFollower {
 public:
  explicit RefereeFollower(bool yellow) : yellow_(yellow) {}
  // A REFEREE message arrived; it takes effect at the first frame sent after
  // its sim time (advance_to), so that which frame first sees a command does
  // not depend on how the two messages raced (sync mode stays reproducible).
  void update(const ubersim::referee_t& referee);
  // Applies, in order, every message judged before sim time t (a frame's t_sent).
  void advance_to(double t);
  GameMode mode() const;
  int goalkeeper() const;  // the referee's goalkeeper id for us, -1 before any message

 private:
  bool yellow_;
  void apply(const ubersim::referee_t& referee);
  std::deque<ubersim::referee_t> waiting_;
  std::optional<ubersim::referee_t> last_;
  std::optional<bool> prepared_by_us_;  // the last PREPARE_* named us
};

// Every own robot stopped.
std::vector<ubersim::robot_command_t> halt(const WorldModel& world);
// Formation, shifted with the ball, every target at least 0.6 m from the ball,
// at most 1 m/s (the SSL limit at STOP is 1.5 m/s).
std::vector<ubersim::robot_command_t> keep_away(const WorldModel& world, const TeamSetup& team);

}  // namespace demo
