#include "ubersim/ssl_bridge/official_referee.hpp"

#include <cmath>
#include <ubersim/team_t.hpp>

namespace ubersim::ssl {
namespace {

constexpr double kMicrosecondsPerSecond = 1e6;
constexpr double kMillimetres = 1e3;
// SSL rules: a restart is taken once the ball moved this far.
constexpr double kInPlayDistance = 0.05;  // m

using google::protobuf::FieldDescriptor;
using google::protobuf::Message;

int8_t lcm_team(int ssl_team) {
  return ssl_team == ::BLUE ? team_t::BLUE : team_t::YELLOW;
}

// The set payload of the event's oneof, nullptr when none is.
const Message* payload(const GameEvent& event) {
  const auto* oneof = GameEvent::descriptor()->FindOneofByName("event");
  const FieldDescriptor* set = event.GetReflection()->GetOneofFieldDescriptor(event, oneof);
  return set == nullptr ? nullptr : &event.GetReflection()->GetMessage(event, set);
}

// The first of `names` the payload has and sets, as a field of the given type.
const FieldDescriptor* set_field(const Message& m, std::initializer_list<const char*> names,
                                 FieldDescriptor::CppType type) {
  for (const char* name : names) {
    const FieldDescriptor* f = m.GetDescriptor()->FindFieldByName(name);
    if (f != nullptr && !f->is_repeated() && f->cpp_type() == type &&
        m.GetReflection()->HasField(m, f)) {
      return f;
    }
  }
  return nullptr;
}

bool restart_waits_for_kick(int command) {
  return command == referee_t::NORMAL_START || command == referee_t::DIRECT_FREE_YELLOW ||
         command == referee_t::DIRECT_FREE_BLUE;
}

void fill_team_info(const Referee::TeamInfo& info, std::string& name, int32_t& score,
                    int32_t& fouls, int32_t& goalkeeper) {
  name = info.name();
  score = static_cast<int32_t>(info.score());
  fouls = static_cast<int32_t>(info.foul_counter());
  goalkeeper = static_cast<int32_t>(info.goalkeeper());
}

}  // namespace

referee_event_t from_ssl_game_event(const GameEvent& event, double sim_time) {
  referee_event_t out{};
  out.type = static_cast<int32_t>(event.type());
  out.sim_time = sim_time;
  out.robot_id = -1;
  out.description = GameEvent::Type_Name(event.type());
  const Message* p = payload(event);
  if (p == nullptr) return out;
  const auto* r = p->GetReflection();
  if (const auto* team = set_field(*p, {"by_team"}, FieldDescriptor::CPPTYPE_ENUM)) {
    out.has_team = true;
    out.team = lcm_team(r->GetEnumValue(*p, team));
  }
  if (const auto* bot = set_field(*p, {"by_bot", "kicking_bot"}, FieldDescriptor::CPPTYPE_UINT32)) {
    out.robot_id = static_cast<int32_t>(r->GetUInt32(*p, bot));
  }
  if (const auto* at =
          set_field(*p, {"location", "ball_location"}, FieldDescriptor::CPPTYPE_MESSAGE)) {
    const auto& v = static_cast<const Vector2&>(r->GetMessage(*p, at));
    if (std::isfinite(v.x()) && std::isfinite(v.y())) {
      out.has_location = true;
      out.location[0] = v.x();  // the game events' locations are in m already
      out.location[1] = v.y();
    }
  }
  if (const auto* text = set_field(*p, {"message"}, FieldDescriptor::CPPTYPE_STRING)) {
    out.description += ": " + r->GetString(*p, text);
  }
  return out;
}

referee_t OfficialRefereeTracker::translate(const Referee& in, const sim_state_t* state) {
  const double now = state != nullptr ? state->sim_time : 0.0;
  const bool has_ball = state != nullptr && state->ball_present;
  const auto counter = static_cast<std::int64_t>(in.command_counter());
  if (counter != last_counter_) {
    last_counter_ = counter;
    command_time_ = now;
    ball_in_play_ = in.command() == Referee::FORCE_START;
    command_ball_[0] = has_ball ? std::optional<double>(state->ball.position[0]) : std::nullopt;
    command_ball_[1] = has_ball ? std::optional<double>(state->ball.position[1]) : std::nullopt;
  }
  if (!ball_in_play_ && restart_waits_for_kick(in.command()) && has_ball) {
    if (!command_ball_[0]) {  // no ball known when the command came: measure from now on
      command_ball_[0] = state->ball.position[0];
      command_ball_[1] = state->ball.position[1];
    }
    ball_in_play_ = std::hypot(state->ball.position[0] - *command_ball_[0],
                               state->ball.position[1] - *command_ball_[1]) >= kInPlayDistance;
  }
  referee_t out{};
  out.sim_time = now;
  out.next_judge_time = now;  // the official game controller does not say when it judges next
  out.stage = static_cast<int8_t>(in.stage());
  out.stage_time_left = static_cast<double>(in.stage_time_left()) / kMicrosecondsPerSecond;
  out.command = static_cast<int8_t>(in.command());
  out.command_counter = static_cast<int32_t>(in.command_counter());
  out.command_time = command_time_;
  out.has_next_command = in.has_next_command();
  out.next_command = static_cast<int8_t>(in.next_command());
  out.ball_in_play = ball_in_play_;
  out.action_time_left =
      static_cast<double>(in.current_action_time_remaining()) / kMicrosecondsPerSecond;
  const auto& place = in.designated_position();
  // A position that is not a number is no position: nothing NaN reaches the teams.
  out.has_designated_position =
      in.has_designated_position() && std::isfinite(place.x()) && std::isfinite(place.y());
  if (out.has_designated_position) {
    out.designated_position[0] = place.x() / kMillimetres;
    out.designated_position[1] = place.y() / kMillimetres;
  }
  out.blue_on_positive_half = in.blue_team_on_positive_half();
  fill_team_info(in.yellow(), out.yellow_name, out.yellow_score, out.yellow_fouls,
                 out.yellow_goalkeeper);
  fill_team_info(in.blue(), out.blue_name, out.blue_score, out.blue_fouls, out.blue_goalkeeper);
  out.game_over = in.stage() == Referee::POST_GAME;
  for (const GameEvent& event : in.game_events()) {
    out.events.push_back(from_ssl_game_event(event, now));
  }
  out.num_events = static_cast<int32_t>(out.events.size());
  return out;
}

}  // namespace ubersim::ssl
