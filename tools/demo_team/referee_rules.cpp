#include "referee_rules.hpp"

#include <cmath>

namespace demo {
namespace {

using ubersim::referee_t;

constexpr double kStopDistance = 0.6;  // m from the ball (rule: 0.5 m), a margin for noise
constexpr double kStopSpeed = 1.0;     // m/s (rule: 1.5 m/s)

}  // namespace

void RefereeFollower::update(const referee_t& referee) {
  constexpr std::size_t kMaxWaiting = 1000;  // bounded: a flood of messages costs nothing
  if (waiting_.size() >= kMaxWaiting) waiting_.pop_front();
  waiting_.push_back(referee);
}

void RefereeFollower::advance_to(double t) {
  while (!waiting_.empty() && waiting_.front().sim_time < t) {
    apply(waiting_.front());
    waiting_.pop_front();
  }
}

int RefereeFollower::goalkeeper() const {
  if (!last_) return -1;
  return yellow_ ? last_->yellow_goalkeeper : last_->blue_goalkeeper;
}

void RefereeFollower::apply(const referee_t& referee) {
  switch (referee.command) {
    case referee_t::PREPARE_KICKOFF_YELLOW:
    case referee_t::PREPARE_PENALTY_YELLOW:
      prepared_by_us_ = yellow_;
      break;
    case referee_t::PREPARE_KICKOFF_BLUE:
    case referee_t::PREPARE_PENALTY_BLUE:
      prepared_by_us_ = !yellow_;
      break;
    default:
      break;
  }
  last_ = referee;
}

GameMode RefereeFollower::mode() const {
  if (!last_) return GameMode::Play;
  const auto& r = *last_;
  switch (r.command) {
    case referee_t::HALT:
    case referee_t::TIMEOUT_YELLOW:
    case referee_t::TIMEOUT_BLUE:
      return GameMode::Halt;
    // The demo team does not place the ball: it keeps away as at a stop, and the
    // official game controller moves on when the placement fails.
    case referee_t::BALL_PLACEMENT_YELLOW:
    case referee_t::BALL_PLACEMENT_BLUE:
    case referee_t::STOP:
      return GameMode::Stop;
    case referee_t::PREPARE_KICKOFF_YELLOW:
    case referee_t::PREPARE_KICKOFF_BLUE:
    case referee_t::PREPARE_PENALTY_YELLOW:
    case referee_t::PREPARE_PENALTY_BLUE:
      return GameMode::Hold;
    case referee_t::NORMAL_START:
      if (r.ball_in_play || !prepared_by_us_) return GameMode::Play;
      return *prepared_by_us_ ? GameMode::Play : GameMode::Hold;
    case referee_t::DIRECT_FREE_YELLOW:
    case referee_t::DIRECT_FREE_BLUE: {
      if (r.ball_in_play) return GameMode::Play;
      const bool ours = (r.command == referee_t::DIRECT_FREE_YELLOW) == yellow_;
      return ours ? GameMode::Play : GameMode::Hold;
    }
    default:
      return GameMode::Play;
  }
}

std::vector<ubersim::robot_command_t> halt(const WorldModel& world) {
  std::vector<ubersim::robot_command_t> commands;
  for (const auto& [id, pose] : world.own()) commands.push_back(local_command(id, pose, 0, 0, 0));
  return commands;
}

std::vector<ubersim::robot_command_t> keep_away(const WorldModel& world, const TeamSetup& team) {
  TeamSetup slow = team;
  slow.limits.max_speed = kStopSpeed;
  auto commands = hold_positions(world, slow);
  if (!world.ball()) return commands;
  const auto& ball = *world.ball();
  std::size_t index = 0;
  for (const auto& [id, pose] : world.own()) {
    // hold_positions gave this robot its formation spot; drive instead to the
    // nearest point outside the ball's circle when the spot or the robot is inside.
    const double dx = pose.x - ball.x, dy = pose.y - ball.y;
    const double distance = std::hypot(dx, dy);
    if (distance < kStopDistance) {
      const double ux =
          distance > 1e-6 ? dx / distance : static_cast<double>(team.defends);  // own goal
      const double uy = distance > 1e-6 ? dy / distance : 0.0;
      commands[index] = go_to(id, pose, ball.x + ux * (kStopDistance + 0.1),
                              ball.y + uy * (kStopDistance + 0.1), pose.orientation, slow.limits);
    }
    ++index;
  }
  return commands;
}

}  // namespace demo
