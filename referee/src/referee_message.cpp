#include "ubersim/referee/referee_message.hpp"

#include <cstdio>
#include <sstream>
#include <ubersim/team_t.hpp>

#include "ubersim/json_string.hpp"

namespace ubersim::referee {
namespace {

int8_t wire(Team team) {
  return team == Team::Blue ? team_t::BLUE : team_t::YELLOW;
}

// Fixed precision: the log of two identical games is byte for byte the same.
std::string number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4f", value);
  return buffer;
}

std::string team_figures(const TeamStats& s) {
  return "{\"goals\": " + std::to_string(s.goals) + ", \"shots\": " + std::to_string(s.shots) +
         ", \"fouls\": " + std::to_string(s.fouls) + ", \"possession\": " + number(s.possession) +
         "}";
}

}  // namespace

referee_event_t to_message(const GameEvent& event) {
  referee_event_t m{};
  m.type = static_cast<int32_t>(event.type);
  m.sim_time = event.sim_time;
  m.has_team = event.team.has_value();
  m.team = event.team ? wire(*event.team) : team_t::YELLOW;
  m.robot_id = event.robot;
  m.has_location = event.has_location;
  m.location[0] = event.x;
  m.location[1] = event.y;
  m.value = event.value;
  m.foul = event.foul;
  m.description = event.description;
  return m;
}

referee_t to_message(const RefereeState& state, const GameConfig& config, FieldSides sides,
                     double sim_time) {
  referee_t m{};
  m.sim_time = sim_time;
  m.next_judge_time = sim_time;  // the runner names the next state it judges
  m.stage = static_cast<int8_t>(state.stage);
  m.stage_time_left = state.stage_time_left;
  m.command = static_cast<int8_t>(state.command);
  m.command_counter = state.command_counter;
  m.command_time = state.command_time;
  m.has_next_command = state.next_command.has_value();
  m.next_command = state.next_command ? static_cast<int8_t>(*state.next_command) : 0;
  m.ball_in_play = state.ball_in_play;
  m.action_time_left = state.action_time_left;
  m.has_designated_position = state.designated_position.has_value();
  if (state.designated_position) {
    m.designated_position[0] = state.designated_position->first;
    m.designated_position[1] = state.designated_position->second;
  }
  m.blue_on_positive_half = sides.defends(Team::Blue) > 0;
  m.yellow_score = state.yellow.goals;
  m.blue_score = state.blue.goals;
  m.yellow_fouls = state.yellow.fouls;
  m.blue_fouls = state.blue.fouls;
  m.yellow_goalkeeper = config.keeper_yellow;
  m.blue_goalkeeper = config.keeper_blue;
  m.yellow_name = config.yellow_name;
  m.blue_name = config.blue_name;
  m.game_over = state.game_over;
  for (const auto& e : state.events) m.events.push_back(to_message(e));
  m.num_events = static_cast<int32_t>(m.events.size());
  return m;
}

std::string event_line(const GameEvent& e) {
  std::ostringstream out;
  out << "{\"t\": " << number(e.sim_time) << ", \"event\": " << json_string(event_name(e.type))
      << ", \"team\": " << (e.team ? json_string(team_name(*e.team)) : "null")
      << ", \"robot\": " << e.robot << ", \"x\": " << number(e.x) << ", \"y\": " << number(e.y)
      << ", \"value\": " << number(e.value) << ", \"foul\": " << (e.foul ? "true" : "false")
      << ", \"description\": " << json_string(e.description) << "}";
  return out.str();
}

std::string command_line(const RefereeState& s, double sim_time) {
  std::ostringstream out;
  out << "{\"t\": " << number(sim_time) << ", \"command\": " << json_string(command_name(s.command))
      << ", \"stage\": " << json_string(stage_name(s.stage)) << ", \"score\": [" << s.yellow.goals
      << ", " << s.blue.goals << "]}";
  return out.str();
}

std::vector<ControlLoss> control_losses(const sync_status_t& status, double end) {
  std::vector<ControlLoss> losses;
  for (int i = 0; i < 2; ++i) {
    // A drop that began after the game's end took nothing from it.
    const bool dropped_now = status.dropped_at[i] >= 0 && status.dropped_at[i] < end;
    if (status.drops[i] <= 0 || (!dropped_now && status.without_control[i] <= 0)) continue;
    const double current = dropped_now ? end - status.dropped_at[i] : 0.0;
    losses.push_back({i == team_t::YELLOW ? "yellow" : "blue", status.client[i], status.drops[i],
                      status.without_control[i] + current});
  }
  return losses;
}

std::string degraded_text(const std::vector<ControlLoss>& losses) {
  std::ostringstream out;
  for (const ControlLoss& loss : losses) {
    out << (out.tellp() == 0 ? "DEGRADED: " : "; ") << loss.team << " without control for "
        << number(loss.without_control) << " s of sim time (sync client '" << loss.client
        << "' dropped " << loss.drops << (loss.drops == 1 ? " time" : " times") << ")";
  }
  return out.str();
}

std::string result_line(const RefereeState& s, double sim_time, double wall_time,
                        const std::vector<ControlLoss>& losses) {
  std::ostringstream out;
  out << "{\"t\": " << number(sim_time) << ", \"result\": " << json_string(stage_name(s.stage))
      << ", \"game_over\": " << (s.game_over ? "true" : "false")
      << ", \"yellow\": " << team_figures(s.yellow) << ", \"blue\": " << team_figures(s.blue);
  if (!losses.empty()) {
    out << ", \"degraded\": [";
    for (std::size_t i = 0; i < losses.size(); ++i) {
      const ControlLoss& loss = losses[i];
      out << (i ? ", " : "") << "{\"team\": " << json_string(loss.team)
          << ", \"client\": " << json_string(loss.client) << ", \"drops\": " << loss.drops
          << ", \"without_control\": " << number(loss.without_control) << "}";
    }
    out << "]";
  }
  out << ", \"wall_time\": " << number(wall_time) << "}";
  return out.str();
}

}  // namespace ubersim::referee
