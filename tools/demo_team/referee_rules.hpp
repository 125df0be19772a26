#pragma once
// How the demo team obeys the referee (referee_t on REFEREE): HALT stands
// still, STOP keeps 0.6 m from the ball at 1 m/s, a kick-off or penalty being
// prepared is held where the referee placed everyone, and a restart belongs to
// the team it names until the ball is in play; the other team waits for it.
// Without any referee message the team just plays.
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
  void update(const ubersim::referee_t& referee);
  GameMode mode() const;

 private:
  bool yellow_;
  std::optional<ubersim::referee_t> last_;
  std::optional<bool> prepared_by_us_;  // the last PREPARE_* named us
};

// Every own robot stopped.
std::vector<ubersim::robot_command_t> halt(const WorldModel& world);
// Formation, shifted with the ball, every target at least 0.6 m from the ball,
// at most 1 m/s (the SSL limit at STOP is 1.5 m/s).
std::vector<ubersim::robot_command_t> keep_away(const WorldModel& world, const TeamSetup& team);

}  // namespace demo
