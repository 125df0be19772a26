#include "ubersim/ssl_bridge/referee_translation.hpp"

#include <cmath>
#include <ubersim/team_t.hpp>

namespace ubersim::ssl {
namespace {

constexpr double kMicroseconds = 1e6;
// What a team has when nothing was used (SSL rules, Division B): 4 timeouts, 5 min.
constexpr std::uint32_t kTimeouts = 4;
constexpr std::uint32_t kTimeoutTime = 300'000'000;  // µs

constexpr double kLatestTime = 1e9;  // s: beyond is no sim time (a hostile bus)

// A duration (may be negative: a stage in overtime); what is not finite or beyond 1e9 s is 0.
std::int64_t micros(double seconds) {
  if (!std::isfinite(seconds) || std::abs(seconds) > kLatestTime) return 0;
  return std::llround(seconds * kMicroseconds);
}

::Team ssl_team(std::int8_t team) {
  return team == team_t::BLUE ? ::BLUE : ::YELLOW;
}

void fill_team(Referee::TeamInfo& info, const std::string& name, std::int32_t score,
               std::int32_t fouls, std::int32_t goalkeeper) {
  info.set_name(name);
  info.set_score(static_cast<std::uint32_t>(std::max(0, score)));
  info.set_red_cards(0);
  info.set_yellow_cards(0);
  info.set_timeouts(kTimeouts);
  info.set_timeout_time(kTimeoutTime);
  info.set_goalkeeper(static_cast<std::uint32_t>(std::max(0, goalkeeper)));
  info.set_foul_counter(static_cast<std::uint32_t>(std::max(0, fouls)));
  info.set_can_place_ball(false);  // the referee places the ball itself
}

template <class Payload>
void locate(Payload* payload, const referee_event_t& e) {
  if (!e.has_location) return;
  payload->mutable_location()->set_x(static_cast<float>(e.location[0]));
  payload->mutable_location()->set_y(static_cast<float>(e.location[1]));
}

}  // namespace

std::uint64_t sim_time_us(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0 || seconds > kLatestTime) return 0;
  return static_cast<std::uint64_t>(std::llround(seconds * kMicroseconds));
}

GameEvent to_ssl_game_event(const referee_event_t& e) {
  GameEvent g;
  g.set_type(static_cast<GameEvent::Type>(e.type));
  g.add_origin("ubersim_referee auto");
  g.set_created_timestamp(sim_time_us(e.sim_time));
  const ::Team team = ssl_team(e.team);
  switch (e.type) {
    case referee_event_t::GOAL: {
      auto* p = g.mutable_goal();
      p->set_by_team(team);
      if (e.robot_id >= 0) p->set_kicking_bot(static_cast<std::uint32_t>(e.robot_id));
      locate(p, e);
      p->set_message(e.description);
      break;
    }
    case referee_event_t::BALL_LEFT_FIELD_TOUCH_LINE:
    case referee_event_t::BALL_LEFT_FIELD_GOAL_LINE: {
      auto* p = e.type == referee_event_t::BALL_LEFT_FIELD_TOUCH_LINE
                    ? g.mutable_ball_left_field_touch_line()
                    : g.mutable_ball_left_field_goal_line();
      p->set_by_team(team);
      if (e.robot_id >= 0) p->set_by_bot(static_cast<std::uint32_t>(e.robot_id));
      locate(p, e);
      break;
    }
    case referee_event_t::BOT_KICKED_BALL_TOO_FAST: {
      auto* p = g.mutable_bot_kicked_ball_too_fast();
      p->set_by_team(team);
      if (e.robot_id >= 0) p->set_by_bot(static_cast<std::uint32_t>(e.robot_id));
      locate(p, e);
      p->set_initial_ball_speed(static_cast<float>(e.value));
      break;
    }
    case referee_event_t::ATTACKER_DOUBLE_TOUCHED_BALL: {
      auto* p = g.mutable_attacker_double_touched_ball();
      p->set_by_team(team);
      if (e.robot_id >= 0) p->set_by_bot(static_cast<std::uint32_t>(e.robot_id));
      locate(p, e);
      break;
    }
    case referee_event_t::DEFENDER_IN_DEFENSE_AREA: {
      auto* p = g.mutable_defender_in_defense_area();
      p->set_by_team(team);
      if (e.robot_id >= 0) p->set_by_bot(static_cast<std::uint32_t>(e.robot_id));
      locate(p, e);
      break;
    }
    case referee_event_t::TOO_MANY_ROBOTS: {
      auto* p = g.mutable_too_many_robots();
      p->set_by_team(team);
      p->set_num_robots_on_field(static_cast<std::int32_t>(e.value));
      if (e.has_location) {
        p->mutable_ball_location()->set_x(static_cast<float>(e.location[0]));
        p->mutable_ball_location()->set_y(static_cast<float>(e.location[1]));
      }
      break;
    }
    case referee_event_t::NO_PROGRESS_IN_GAME: {
      auto* p = g.mutable_no_progress_in_game();
      locate(p, e);
      p->set_time(static_cast<float>(e.value));
      break;
    }
    default:
      break;  // the type alone
  }
  return g;
}

Referee RefereeTranslator::translate(const referee_t& r) const {
  Referee m;
  m.set_source_identifier(source_identifier_);
  m.set_match_type(FRIENDLY);
  m.set_packet_timestamp(sim_time_us(r.sim_time));
  m.set_stage(static_cast<Referee::Stage>(r.stage));
  m.set_stage_time_left(micros(r.stage_time_left));
  m.set_command(static_cast<Referee::Command>(r.command));
  m.set_command_counter(static_cast<std::uint32_t>(r.command_counter));
  m.set_command_timestamp(sim_time_us(r.command_time));
  fill_team(*m.mutable_yellow(), r.yellow_name, r.yellow_score, r.yellow_fouls,
            r.yellow_goalkeeper);
  fill_team(*m.mutable_blue(), r.blue_name, r.blue_score, r.blue_fouls, r.blue_goalkeeper);
  // The protocol has a designated position only with a BALL_PLACEMENT_*
  // command, which this referee never gives (it places the ball itself).
  m.set_blue_team_on_positive_half(r.blue_on_positive_half);
  if (r.has_next_command) m.set_next_command(static_cast<Referee::Command>(r.next_command));
  for (const auto& e : r.events) *m.add_game_events() = to_ssl_game_event(e);
  if (r.action_time_left > 0) m.set_current_action_time_remaining(micros(r.action_time_left));
  if (!r.events.empty()) m.set_status_message(r.events.back().description);
  return m;
}

}  // namespace ubersim::ssl
