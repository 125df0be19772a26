#include "ubersim/gc_link/field_keeper.hpp"

#include <cmath>

namespace ubersim::gc_link {
namespace {

using referee::Situation;
using referee::SituationRequest;
using ubersim::Team;

// The kick-off or penalty a command announces, if it is one.
std::optional<SituationRequest> set_piece(Referee::Command command) {
  switch (command) {
    case Referee::PREPARE_KICKOFF_YELLOW:
      return SituationRequest{Situation::KickOff, Team::Yellow};
    case Referee::PREPARE_KICKOFF_BLUE:
      return SituationRequest{Situation::KickOff, Team::Blue};
    case Referee::PREPARE_PENALTY_YELLOW:
      return SituationRequest{Situation::Penalty, Team::Yellow};
    case Referee::PREPARE_PENALTY_BLUE:
      return SituationRequest{Situation::Penalty, Team::Blue};
    default:
      return std::nullopt;
  }
}

}  // namespace

std::optional<SituationRequest> FieldKeeper::decide(const Referee& gc, const sim_state_t& state) {
  const double now = state.sim_time;
  if (counter_ != gc.command_counter()) {
    counter_ = gc.command_counter();
    since_ = now;
  }
  if (auto piece = set_piece(gc.command())) {
    if (prepared_ == gc.command_counter()) return std::nullopt;
    prepared_ = gc.command_counter();
    last_placed_ = now;
    return piece;
  }
  const bool stoppage = gc.command() == Referee::STOP || gc.command() == Referee::HALT;
  if (!stoppage || now - since_ < kHold || now - last_placed_ < kHold) return std::nullopt;
  if (gc.has_next_command()) {
    if (auto piece = set_piece(gc.next_command())) {
      if (prepared_ == gc.command_counter()) return std::nullopt;
      prepared_ = gc.command_counter();  // once per stop: the teams keep their distance
      last_placed_ = now;
      return piece;
    }
  }
  if (!gc.has_designated_position() || !state.ball_present) return std::nullopt;
  const double x = gc.designated_position().x() / 1000.0;
  const double y = gc.designated_position().y() / 1000.0;
  if (!std::isfinite(x) || !std::isfinite(y)) return std::nullopt;
  if (std::hypot(state.ball.position[0] - x, state.ball.position[1] - y) <= kTolerance) {
    return std::nullopt;
  }
  last_placed_ = now;
  return SituationRequest{Situation::BallPlacement, Team::Yellow, x, y};
}

}  // namespace ubersim::gc_link
