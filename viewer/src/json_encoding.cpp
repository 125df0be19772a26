#include "ubersim/viewer/json_encoding.hpp"

#include <cmath>
#include <iterator>
#include <string_view>
#include <type_traits>
#include <ubersim/lcm_fields.hpp>
#include <ubersim/team_t.hpp>

#include "ubersim/viewer/request_policy.hpp"

namespace ubersim::viewer {
namespace {

using nlohmann::json;

// Millimetre / milliradian resolution is far finer than any pixel on the page,
// and short numbers keep a 22-robot frame small at 60 Hz.
json number(double value, double resolution = 1e-4) {
  if (!std::isfinite(value)) return nullptr;
  return std::round(value / resolution) * resolution;
}

const char* team_text(int team) {
  switch (team) {
    case team_t::YELLOW:
      return "yellow";
    case team_t::BLUE:
      return "blue";
    default:
      return "unknown";
  }
}

const char* mode_text(int mode) {
  switch (mode) {
    case robot_command_t::MODE_LOCAL_VELOCITY:
      return "local";
    case robot_command_t::MODE_GLOBAL_VELOCITY:
      return "global";
    case robot_command_t::MODE_WHEEL_SPEEDS:
      return "wheels";
    default:
      return "unknown";
  }
}

json encode_vision_robots(const std::vector<vision_robot_t>& robots) {
  json out = json::array();
  for (const auto& robot : robots) {
    out.push_back({{"id", robot.robot_id},
                   {"x", number(robot.x)},
                   {"y", number(robot.y)},
                   {"orientation", number(robot.orientation)},
                   {"confidence", number(robot.confidence, 1e-3)}});
  }
  return out;
}

// The SSL names (ssl_gc_referee_message.proto) of referee_t's stages and
// commands; a number this viewer does not know is shown as one.
std::string stage_text(int stage) {
  static const char* const kStages[] = {
      "NORMAL_FIRST_HALF_PRE",  "NORMAL_FIRST_HALF",  "NORMAL_HALF_TIME",
      "NORMAL_SECOND_HALF_PRE", "NORMAL_SECOND_HALF", "EXTRA_TIME_BREAK",
      "EXTRA_FIRST_HALF_PRE",   "EXTRA_FIRST_HALF",   "EXTRA_HALF_TIME",
      "EXTRA_SECOND_HALF_PRE",  "EXTRA_SECOND_HALF",  "PENALTY_SHOOTOUT_BREAK",
      "PENALTY_SHOOTOUT",       "POST_GAME"};
  if (stage >= 0 && stage < static_cast<int>(std::size(kStages))) return kStages[stage];
  return "STAGE " + std::to_string(stage);
}

// The name of Msg's .lcm constant with that value, leaving out those whose
// names begin with `skip`; nullptr when there is none.
template <class Msg>
const char* constant_name(std::int64_t value, std::string_view skip = {}) {
  for (const LcmConstant& constant : LcmFields<Msg>::kConstants) {
    if (!skip.empty() && std::string_view(constant.name).substr(0, skip.size()) == skip) continue;
    if (constant.value == value) return constant.name;
  }
  return nullptr;
}

// referee_t's command constants (its others are the STAGE_*s) and
// referee_event_t's, by their .lcm names; a number not there is shown as one.
std::string command_text(int command) {
  const char* name = constant_name<referee_t>(command, "STAGE_");
  return name != nullptr ? name : "COMMAND " + std::to_string(command);
}

std::string event_type_text(int type) {
  const char* name = constant_name<referee_event_t>(type);
  return name != nullptr ? name : "EVENT " + std::to_string(type);
}

json encode_referee_team(std::int32_t score, std::int32_t fouls, std::int32_t goalkeeper) {
  return {{"score", score}, {"fouls", fouls}, {"goalkeeper", goalkeeper}};
}

// The teams' names, when the message has them (HasTeamNames).
template <typename Referee>
void add_team_names(const Referee& r, json& yellow, json& blue) {
  if constexpr (HasTeamNames<Referee>::value) {
    yellow["name"] = r.yellow_name;
    blue["name"] = r.blue_name;
  }
}

bool finite_number(const json& value) {
  return value.is_number() && std::isfinite(value.get<double>());
}

}  // namespace

json encode_sim_state(const sim_state_t& state) {
  json robots = json::array();
  for (const auto& robot : state.robots) {
    robots.push_back({{"team", team_text(robot.team)},
                      {"id", robot.robot_id},
                      {"type", robot.robot_type},
                      {"x", number(robot.x)},
                      {"y", number(robot.y)},
                      {"orientation", number(robot.orientation)},
                      {"vx", number(robot.vx)},
                      {"vy", number(robot.vy)},
                      {"omega", number(robot.omega)},
                      {"ball_contact", static_cast<bool>(robot.ball_contact)}});
  }
  json ball = nullptr;
  if (state.ball_present) {
    const auto& b = state.ball;
    ball = {{"x", number(b.position[0])},         {"y", number(b.position[1])},
            {"z", number(b.position[2])},         {"vx", number(b.linear_velocity[0])},
            {"vy", number(b.linear_velocity[1])}, {"vz", number(b.linear_velocity[2])}};
  }
  return {{"sim_time", number(state.sim_time, 1e-6)},
          {"step", state.step},
          {"paused", static_cast<bool>(state.paused)},
          {"speed_factor", number(state.speed_factor, 1e-6)},
          {"ball", ball},
          {"robots", robots}};
}

json encode_vision_frame(const vision_frame_t& frame) {
  json balls = json::array();
  for (const auto& ball : frame.balls) {
    balls.push_back({{"x", number(ball.x)},
                     {"y", number(ball.y)},
                     {"confidence", number(ball.confidence, 1e-3)}});
  }
  return {{"camera_id", frame.camera_id},
          {"frame_number", frame.frame_number},
          {"t_capture", number(frame.t_capture, 1e-6)},
          {"t_sent", number(frame.t_sent, 1e-6)},
          {"balls", balls},
          {"yellow", encode_vision_robots(frame.robots_yellow)},
          {"blue", encode_vision_robots(frame.robots_blue)}};
}

json encode_field_geometry(const field_geometry_t& f) {
  // Every field of the message under its .lcm name (the page draws from them).
  json out = json::object();
  auto add = [&out](const std::string& name, const auto& value, FieldKind kind) {
    if constexpr (std::is_arithmetic_v<std::decay_t<decltype(value)>>) {
      if (kind == FieldKind::kReal) {
        out[name] = number(value);
        return;
      }
    }
    out[name] = value;
  };
  LcmFields<field_geometry_t>::visit(f, "", add);
  return out;
}

json encode_cameras(const vision_geometry_t& geometry) {
  json cameras = json::array();
  for (const auto& camera : geometry.cameras) {
    cameras.push_back({{"camera_id", camera.camera_id},
                       {"x", number(camera.position[0])},
                       {"y", number(camera.position[1])},
                       {"z", number(camera.position[2])}});
  }
  return cameras;
}

json encode_radio_packet(const radio_packet_t& packet) {
  json commands = json::array();
  for (const auto& command : packet.commands) {
    commands.push_back({{"id", command.robot_id},
                        {"mode", mode_text(command.mode)},
                        {"vx", number(command.vx)},
                        {"vy", number(command.vy)},
                        {"omega", number(command.omega)},
                        {"kick", number(command.kick_speed)},
                        {"chip", number(command.chip_speed)},
                        {"dribbler", number(command.dribbler_speed)}});
  }
  return {{"team", team_text(packet.team)},
          {"sequence", packet.sequence},
          {"t_sent", number(packet.t_sent, 1e-6)},
          {"commands", commands}};
}

json encode_referee(const referee_t& r) {
  // The newest few: a hostile message's thousands would only bloat every frame.
  constexpr std::size_t kEventsShown = 8;
  json events = json::array();
  const std::size_t first = r.events.size() > kEventsShown ? r.events.size() - kEventsShown : 0;
  for (std::size_t i = first; i < r.events.size(); ++i) {
    const auto& event = r.events[i];
    json team = nullptr;
    if (event.has_team) team = team_text(event.team);
    events.push_back({{"type", event_type_text(event.type)},
                      {"team", team},
                      {"description", event.description}});
  }
  json next_command = nullptr;
  if (r.has_next_command) next_command = command_text(r.next_command);
  json yellow = encode_referee_team(r.yellow_score, r.yellow_fouls, r.yellow_goalkeeper);
  json blue = encode_referee_team(r.blue_score, r.blue_fouls, r.blue_goalkeeper);
  add_team_names(r, yellow, blue);
  return {{"sim_time", number(r.sim_time, 1e-6)},
          {"stage", stage_text(r.stage)},
          {"stage_time_left", number(r.stage_time_left, 1e-3)},
          {"command", command_text(r.command)},
          {"command_counter", r.command_counter},
          {"next_command", next_command},
          {"ball_in_play", static_cast<bool>(r.ball_in_play)},
          {"action_time_left", number(r.action_time_left, 1e-3)},
          {"game_over", static_cast<bool>(r.game_over)},
          {"yellow", yellow},
          {"blue", blue},
          {"events", events}};
}

json encode_ack(const sim_control_ack_t& ack) {
  return {{"request_id", ack.request_id},
          {"ok", static_cast<bool>(ack.ok)},
          {"message", ack.message},
          {"sim_time", number(ack.sim_time, 1e-6)}};
}

ParsedControl parse_control_request(const std::string& text, std::int64_t request_id,
                                    const std::string& sender) {
  if (!json_depth_within(text, kMaxJsonDepth)) {
    return {std::nullopt, "nested deeper than " + std::to_string(kMaxJsonDepth) + " levels"};
  }
  const json request = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (request.is_discarded() || !request.is_object()) return {std::nullopt, "not a JSON object"};
  const auto action_it = request.find("action");
  if (action_it == request.end() || !action_it->is_string()) {
    return {std::nullopt, "no \"action\" string"};
  }
  const std::string action = action_it->get<std::string>();
  // A number the request must carry, finite and within +-limit.
  const auto read = [&request](const char* key, double limit, double& out) {
    const auto it = request.find(key);
    if (it == request.end() || !finite_number(*it)) return false;
    out = it->get<double>();
    return std::abs(out) <= limit;
  };

  sim_control_t control{};
  control.request_id = request_id;
  control.sender = sender;
  control.num_robots = 0;
  control.has_ball = false;
  if (action == "pause") {
    control.action = sim_control_t::PAUSE;
  } else if (action == "resume") {
    control.action = sim_control_t::RESUME;
  } else if (action == "reset") {
    control.action = sim_control_t::RESET;
  } else if (action == "speed") {
    control.action = sim_control_t::SET_SPEED;
    if (!read("factor", kMaxSpeedFactor, control.speed_factor) || control.speed_factor < 0) {
      return {std::nullopt, "speed needs \"factor\" in [0, 100] (0 = as fast as possible)"};
    }
  } else if (action == "place_ball") {
    control.action = sim_control_t::PLACE;
    control.has_ball = true;
    if (!read("x", kMaxPlacementDistance, control.ball.position[0]) ||
        !read("y", kMaxPlacementDistance, control.ball.position[1])) {
      return {std::nullopt, "place_ball needs finite \"x\" and \"y\" within 20 m"};
    }
  } else if (action == "place_robot") {
    control.action = sim_control_t::PLACE;
    robot_placement_t robot{};
    const auto team = request.find("team");
    if (team == request.end() || !team->is_string() || (*team != "yellow" && *team != "blue")) {
      return {std::nullopt, "place_robot needs \"team\": \"yellow\" or \"blue\""};
    }
    robot.team = *team == "yellow" ? team_t::YELLOW : team_t::BLUE;
    const auto id = request.find("id");
    if (id == request.end() || !id->is_number_integer() || id->get<std::int64_t>() < 0 ||
        id->get<std::int64_t>() > 1000) {
      return {std::nullopt, "place_robot needs an integer \"id\" in [0, 1000]"};
    }
    robot.robot_id = id->get<std::int32_t>();
    robot.present = true;  // the page moves robots; it never removes one
    if (!read("x", kMaxPlacementDistance, robot.x) || !read("y", kMaxPlacementDistance, robot.y)) {
      return {std::nullopt, "place_robot needs finite \"x\" and \"y\" within 20 m"};
    }
    if (request.contains("orientation") && !read("orientation", 100.0, robot.orientation)) {
      return {std::nullopt, "place_robot: \"orientation\" must be a finite angle (rad)"};
    }
    control.robots.push_back(robot);
    control.num_robots = 1;
  } else {
    return {std::nullopt, "unknown action \"" + action + "\""};
  }
  return {control, ""};
}

}  // namespace ubersim::viewer
