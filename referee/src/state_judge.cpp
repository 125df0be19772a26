#include "ubersim/referee/state_judge.hpp"

#include <algorithm>
#include <cmath>
#include <exception>

#include "ubersim/logging.hpp"
#include "ubersim/referee/referee_message.hpp"
#include "ubersim/referee/scene_io.hpp"
#include "ubersim/sim_state_numbers.hpp"

namespace ubersim::referee {
namespace {

constexpr double kPublishPeriod = 0.1;  // s of sim time between unchanged referee_t

// A state the simulation could have sent (sim_state_numbers.hpp), with a step that
// is a number too: anyone on the bus may send another.
bool judgeable(const sim_state_t& state) {
  return sim_state_numbers_fit(state) && state_number_fits(state.dt);
}

}  // namespace

StateJudge::StateJudge(JudgeOptions options, field_geometry_t field,
                       std::function<double(const std::string&)> radius_of)
    : options_(std::move(options)),
      field_(std::move(field)),
      radius_of_(std::move(radius_of)),
      referee_(options_.game, field_, options_.sides) {}

bool StateJudge::judges(const sim_state_t& state) const {
  if (options_.judge_every_step || !judged_any_) return true;
  if (state.sim_time < last_time_) return true;  // the simulation was reset
  return state.sim_time >= next_judge_ - 1e-6 * std::max(state.dt, 1e-6);
}

std::optional<sim_control_t> StateJudge::place(const SituationRequest& request,
                                               const sim_state_t& state) {
  const auto before = scene_from_state(state, field_.ball_radius, radius_of_);
  try {
    const auto planned = plan_situation(request, before, field_, options_.sides);
    return place_request(before, planned, true, true);
  } catch (const std::exception& error) {
    spdlog::warn("cannot place the restart: {}", error.what());
    return std::nullopt;
  }
}

JudgeOutput StateJudge::on_state(const sim_state_t& state) {
  JudgeOutput out;
  if (!judgeable(state)) {
    ++refused_;
    return out;
  }
  if (!judges(state)) return out;
  out.judged = true;
  ++judged_;
  judged_any_ = true;
  const auto decision = referee_.update(state);
  const auto& s = referee_.state();
  for (const auto& e : decision.events) {
    spdlog::info("{:.2f} s: {} ({})", e.sim_time, event_name(e.type), e.description);
    out.log_lines.push_back(event_line(e));
  }
  if (decision.placement) out.placement = place(*decision.placement, state);
  if (decision.command_changed) {
    spdlog::info("{:.2f} s: {} [{}] {}:{}", state.sim_time, command_name(s.command),
                 stage_name(s.stage), s.yellow.goals, s.blue.goals);
    out.log_lines.push_back(command_line(s, state.sim_time));
  }
  next_judge_ =
      options_.judge_every_step ? state.sim_time + state.dt : referee_.next_judge_time(state);
  if (options_.sync || decision.command_changed || !decision.events.empty() ||
      state.sim_time - last_publish_ >= kPublishPeriod || state.sim_time < last_publish_) {
    out.referee = to_message(s, options_.game, options_.sides, state.sim_time);
    out.referee->next_judge_time = next_judge_;
    last_publish_ = state.sim_time;
  }
  last_time_ = state.sim_time;
  out.game_over = decision.game_over;
  return out;
}

}  // namespace ubersim::referee
