#pragma once
// What the viewer page receives and sends, as JSON. Every message the server
// pushes is built here from LCM messages, so the page never sees LCM and the
// encoding can be tested without a browser. Lengths in m, angles in rad,
// times in s (sim time), like the messages they come from; non-finite numbers
// become null (JSON has no NaN).
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <type_traits>
#include <ubersim/field_geometry_t.hpp>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/referee_t.hpp>
#include <ubersim/sim_control_ack_t.hpp>
#include <ubersim/sim_control_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <ubersim/vision_frame_t.hpp>
#include <ubersim/vision_geometry_t.hpp>

namespace ubersim::viewer {

// {sim_time, step, paused, speed_factor, ball: {x,y,z,vx,vy,vz} | null,
//  robots: [{team: "yellow"|"blue", id, type, x, y, orientation, vx, vy, omega, ball_contact}]}
nlohmann::json encode_sim_state(const sim_state_t& state);

// {camera_id, frame_number, t_capture, t_sent, balls: [{x, y, confidence}],
//  yellow: [{id, x, y, orientation, confidence}], blue: [...]}
nlohmann::json encode_vision_frame(const vision_frame_t& frame);

// Every field_geometry_t field by its name.
nlohmann::json encode_field_geometry(const field_geometry_t& field);

// [{camera_id, x, y, z}] : where each camera hangs, from a vision_geometry_t.
nlohmann::json encode_cameras(const vision_geometry_t& geometry);

// {team, sequence, t_sent, commands: [{id, mode: "local"|"global"|"wheels", vx, vy, omega,
//  kick, chip, dribbler}]}
nlohmann::json encode_radio_packet(const radio_packet_t& packet);

// Whether referee_t carries the teams' names (yellow_name, blue_name): it does
// once the referee's team names are in the tree; until then the page shows colours.
template <typename Referee, typename = void>
struct HasTeamNames : std::false_type {};
template <typename Referee>
struct HasTeamNames<Referee,
                    std::void_t<decltype(Referee::yellow_name), decltype(Referee::blue_name)>>
    : std::true_type {};

// The game state on REFEREE, stages and commands by their SSL names:
// {sim_time, stage: "NORMAL_FIRST_HALF", stage_time_left, command: "STOP", command_counter,
//  next_command: "PREPARE_KICKOFF_BLUE" | null, ball_in_play, action_time_left, game_over,
//  yellow: {score, fouls, goalkeeper, name (when the message has names)}, blue: {...},
//  events: [{type: "GOAL", team: "yellow"|"blue"|null, description}] (the newest 8)}
nlohmann::json encode_referee(const referee_t& referee);

// {request_id, ok, message, sim_time}
nlohmann::json encode_ack(const sim_control_ack_t& ack);

// A control request from the page, e.g. {"action":"pause"}, {"action":"speed","factor":2},
// {"action":"place_ball","x":0.5,"y":-1}, {"action":"place_robot","team":"blue","id":3,
// "x":1,"y":2,"orientation":0}. Actions: pause, resume, reset, speed, place_ball, place_robot.
struct ParsedControl {
  std::optional<sim_control_t> request;  // set when the text was a valid request
  std::string error;                     // why not, otherwise
};
// Coordinates beyond this (m) from the centre are refused (no field is that big).
inline constexpr double kMaxPlacementDistance = 20.0;
// Speed factors beyond this are refused (physics takes any; a typo should not).
inline constexpr double kMaxSpeedFactor = 100.0;
ParsedControl parse_control_request(const std::string& text, std::int64_t request_id,
                                    const std::string& sender);

}  // namespace ubersim::viewer
