#include "ubersim/gc_link/gc_link.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <sstream>

#include "ubersim/json_string.hpp"
#include "ubersim/logging.hpp"
#include "ubersim/referee/scene_io.hpp"
#include "ubersim/sim_state_numbers.hpp"

namespace ubersim::gc_link {
namespace {

constexpr const char* kTrackerUuid = "ubersim-gc-link";  // fixed: runs stay byte-identical

// Fixed precision: two identical games give byte-identical logs.
std::string number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4f", value);
  return buffer;
}

std::string team_figures(const Referee::TeamInfo& t) {
  return "{\"goals\": " + std::to_string(t.score()) +
         ", \"fouls\": " + std::to_string(t.foul_counter()) +
         ", \"yellow_cards\": " + std::to_string(t.yellow_cards()) +
         ", \"red_cards\": " + std::to_string(t.red_cards()) + "}";
}

// The first step at or after `time`, a hair earlier so that a time that is
// exactly a step is that step.
double step_at_or_after(double now, double time, double dt) {
  const double steps = std::max(1.0, std::ceil((time - now) / dt - 1e-6));
  return now + steps * dt;
}

}  // namespace

referee::GameConfig detector_config(referee::GameConfig rules) {
  rules.game_length = 1e7;  // the GC ends the halves
  rules.halves = 1;
  rules.stop_duration = 0.05;  // back to judging soon after its own restarts
  rules.prepare_duration = 0.05;
  rules.restart_timeout = 1e7;   // the GC times the restarts
  rules.no_progress_time = 1e7;  // and judges progress
  return rules;
}

GcLink::GcLink(LinkOptions options, field_geometry_t field,
               std::function<double(const std::string&)> radius_of)
    : options_(std::move(options)),
      field_(std::move(field)),
      radius_of_(std::move(radius_of)),
      detectors_(detector_config(options_.detectors), field_, options_.setup.sides),
      frames_(ssl::TrackedSettings{1e9, std::nullopt, kTrackerUuid}) {}

void GcLink::set_field(const field_geometry_t& field) {
  field_ = field;
  detectors_.set_field(field);
  geometry_due_ = true;
}

bool GcLink::judges(const sim_state_t& state) const {
  if (!judged_any_ || state.sim_time < last_time_) return true;
  return state.sim_time >= next_judge_ - 1e-6 * std::max(state.dt, 1e-6);
}

std::vector<Input> GcLink::reports_for(const referee::Decision& decision) {
  std::vector<Input> out;
  if (!reports_wanted(gc_)) return out;  // the GC has stopped play: nothing to report
  for (const auto& event : decision.events) {
    if (auto input = report(event)) {
      out.push_back(std::move(*input));
      ++reports_;
    }
  }
  return out;
}

CiInput GcLink::tick_input(const sim_state_t& state) {
  CiInput tick;
  tick.set_timestamp(std::llround(state.sim_time * 1e9));
  auto frames = frames_.on_state(state);
  if (!frames.empty()) *tick.mutable_tracker_packet() = std::move(frames.back());
  if (geometry_due_) {
    *tick.mutable_geometry() = geometry_data(field_);
    geometry_due_ = false;
  }
  return tick;
}

std::optional<CiConversation> GcLink::begin(const sim_state_t& state) {
  in_conversation_ = false;
  if (!sim_state_numbers_fit(state) || !state_number_fits(state.dt)) {
    ++refused_;
    return std::nullopt;
  }
  if (over_ || !judges(state)) return std::nullopt;
  const auto decision = detectors_.update(state);
  next_detect_ = detectors_.next_judge_time(state);
  std::vector<Input> changes;
  if (!operator_.started()) changes = setup_inputs(options_.setup);
  for (Input& input : operator_.decide(gc_, state.sim_time)) changes.push_back(std::move(input));
  for (Input& input : reports_for(decision)) changes.push_back(std::move(input));
  if (state.sim_time < next_tick_ - 1e-9 && changes.empty()) return std::nullopt;
  in_conversation_ = true;
  ++ticks_;
  const double dt = state.dt > 0 ? state.dt : 1.0 / 240;
  next_tick_ = step_at_or_after(state.sim_time, state.sim_time + options_.tick_period, dt);
  return CiConversation(tick_input(state), std::move(changes), barriers_);
}

std::optional<sim_control_t> GcLink::place(const referee::SituationRequest& request,
                                           const sim_state_t& state) const {
  const auto before = referee::scene_from_state(state, field_.ball_radius, radius_of_);
  try {
    const auto planned = referee::plan_situation(request, before, field_, options_.setup.sides);
    const bool set_piece = request.kind != referee::Situation::BallPlacement;
    return referee::place_request(before, planned, true, set_piece);
  } catch (const std::exception& error) {
    spdlog::warn("cannot place what the game controller asks: {}", error.what());
    return std::nullopt;
  }
}

void GcLink::log_changes(const sim_state_t& state, LinkOutput& out) {
  const double t = state.sim_time;
  if (logged_counter_ != gc_.command_counter() || logged_yellow_ != gc_.yellow().score() ||
      logged_blue_ != gc_.blue().score()) {
    logged_counter_ = gc_.command_counter();
    logged_yellow_ = gc_.yellow().score();
    logged_blue_ = gc_.blue().score();
    logged_events_ = std::min(logged_events_, gc_.game_events_size());
    std::ostringstream line;
    line << "{\"t\": " << number(t)
         << ", \"command\": " << json_string(Referee::Command_Name(gc_.command()))
         << ", \"stage\": " << json_string(Referee::Stage_Name(gc_.stage())) << ", \"score\": ["
         << gc_.yellow().score() << ", " << gc_.blue().score() << "]}";
    out.log_lines.push_back(line.str());
    spdlog::info("{:.2f} s: {} [{}] {}:{}", t, Referee::Command_Name(gc_.command()),
                 Referee::Stage_Name(gc_.stage()), gc_.yellow().score(), gc_.blue().score());
  }
  if (gc_.game_events_size() < logged_events_) logged_events_ = 0;  // a new list (play resumed)
  for (; logged_events_ < gc_.game_events_size(); ++logged_events_) {
    const auto event = ssl::from_ssl_game_event(gc_.game_events(logged_events_), t);
    const char* team = !event.has_team ? "null" : event.team == 0 ? "\"yellow\"" : "\"blue\"";
    std::ostringstream line;
    line << "{\"t\": " << number(t) << ", \"event\": "
         << json_string(GameEvent::Type_Name(gc_.game_events(logged_events_).type()))
         << ", \"team\": " << team << ", \"robot\": " << event.robot_id
         << ", \"x\": " << number(event.location[0]) << ", \"y\": " << number(event.location[1])
         << ", \"description\": " << json_string(event.description) << "}";
    out.log_lines.push_back(line.str());
    spdlog::info("{:.2f} s: {}", t, event.description);
  }
}

LinkOutput GcLink::finish(const sim_state_t& state, const CiConversation* conversation) {
  LinkOutput out;
  if (!sim_state_numbers_fit(state) || !state_number_fits(state.dt) || over_ || !judges(state)) {
    return out;
  }
  out.judged = true;
  ++judged_;
  judged_any_ = true;
  if (conversation != nullptr) {
    gc_ = conversation->referee();
    log_changes(state, out);
  }
  if (auto request = keeper_.decide(gc_, state)) out.placement = place(*request, state);
  const double dt = state.dt > 0 ? state.dt : 1.0 / 240;
  next_judge_ = std::min(next_detect_, step_at_or_after(state.sim_time, next_tick_, dt));
  out.referee = translation_.translate(gc_, &state);
  out.referee->next_judge_time = next_judge_;
  out.game_over = gc_.stage() == Referee::POST_GAME;
  out.referee->game_over = out.game_over;
  over_ = out.game_over;
  last_time_ = state.sim_time;
  return out;
}

std::string GcLink::result_line(double wall_time) const {
  std::ostringstream out;
  out << "{\"t\": " << number(last_time_)
      << ", \"result\": " << json_string(Referee::Stage_Name(gc_.stage()))
      << ", \"game_over\": " << (over_ ? "true" : "false")
      << ", \"yellow\": " << team_figures(gc_.yellow())
      << ", \"blue\": " << team_figures(gc_.blue()) << ", \"wall_time\": " << number(wall_time)
      << "}";
  return out.str();
}

}  // namespace ubersim::gc_link
