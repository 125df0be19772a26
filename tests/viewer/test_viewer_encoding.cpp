// The viewer's message-to-JSON encoding, the page's control requests, and the
// coalescing model: what the page receives is exactly what was published.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <ubersim/referee_t.hpp>
#include <ubersim/team_t.hpp>

#include "ubersim/viewer/json_encoding.hpp"
#include "ubersim/viewer/rate_meter.hpp"
#include "ubersim/viewer/viewer_model.hpp"

namespace ubersim::viewer {
namespace {

using nlohmann::json;

robot_state_t robot(int8_t team, int id, double x, double y, double orientation) {
  robot_state_t r{};
  r.team = team;
  r.robot_id = id;
  r.robot_type = "omni4_ssl";
  r.x = x;
  r.y = y;
  r.orientation = orientation;
  r.vx = 0.5;
  r.vy = -0.25;
  r.omega = 1.5;
  r.num_wheels = 0;
  r.last_command_time = -1;
  return r;
}

sim_state_t two_robot_state(double sim_time) {
  sim_state_t state{};
  state.sim_time = sim_time;
  state.step = static_cast<int64_t>(sim_time * 240);
  state.dt = 1.0 / 240;
  state.paused = false;
  state.speed_factor = 1;
  state.ball_present = true;
  state.ball.position[0] = 1.25;
  state.ball.position[1] = -0.5;
  state.ball.position[2] = 0.0215;
  state.ball.linear_velocity[0] = 3;
  state.ball.orientation[0] = 1;
  state.robots = {robot(team_t::YELLOW, 3, -1.5, 0.75, 0.5),
                  robot(team_t::BLUE, 7, 2.0, -1.0, -3.0)};
  state.num_robots = 2;
  return state;
}

TEST(ViewerEncoding, SimStateCarriesEveryRobotAndTheBall) {
  const json j = encode_sim_state(two_robot_state(12.5));
  EXPECT_DOUBLE_EQ(j["sim_time"].get<double>(), 12.5);
  EXPECT_EQ(j["step"], 3000);
  EXPECT_EQ(j["paused"], false);
  EXPECT_DOUBLE_EQ(j["speed_factor"].get<double>(), 1.0);
  ASSERT_EQ(j["robots"].size(), 2u);
  const json& yellow = j["robots"][0];
  EXPECT_EQ(yellow["team"], "yellow");
  EXPECT_EQ(yellow["id"], 3);
  EXPECT_EQ(yellow["type"], "omni4_ssl");
  EXPECT_DOUBLE_EQ(yellow["x"].get<double>(), -1.5);
  EXPECT_DOUBLE_EQ(yellow["y"].get<double>(), 0.75);
  EXPECT_DOUBLE_EQ(yellow["orientation"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(yellow["vx"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(yellow["vy"].get<double>(), -0.25);
  EXPECT_DOUBLE_EQ(yellow["omega"].get<double>(), 1.5);
  EXPECT_EQ(j["robots"][1]["team"], "blue");
  EXPECT_EQ(j["robots"][1]["id"], 7);
  EXPECT_DOUBLE_EQ(j["ball"]["x"].get<double>(), 1.25);
  EXPECT_DOUBLE_EQ(j["ball"]["y"].get<double>(), -0.5);
  EXPECT_DOUBLE_EQ(j["ball"]["vx"].get<double>(), 3.0);
}

TEST(ViewerEncoding, PositionsAreRoundedToATenthOfAMillimetreAndNonFiniteBecomesNull) {
  sim_state_t state = two_robot_state(1);
  state.robots[0].x = 0.123456789;
  state.robots[0].y = std::numeric_limits<double>::quiet_NaN();
  state.robots[0].orientation = std::numeric_limits<double>::infinity();
  const json j = encode_sim_state(state);
  EXPECT_NEAR(j["robots"][0]["x"].get<double>(), 0.1235, 1e-12);
  EXPECT_TRUE(j["robots"][0]["y"].is_null());
  EXPECT_TRUE(j["robots"][0]["orientation"].is_null());
  // The text stays short: no 17-digit numbers on the wire.
  EXPECT_EQ(j.dump().find("0.12345"), std::string::npos);
  EXPECT_NE(j.dump().find("\"x\":0.1235"), std::string::npos) << j.dump();
}

TEST(ViewerEncoding, MissingBallIsNull) {
  sim_state_t state = two_robot_state(1);
  state.ball_present = false;
  EXPECT_TRUE(encode_sim_state(state)["ball"].is_null());
}

TEST(ViewerEncoding, VisionFrameKeepsCameraTimesAndDetectionsPerTeam) {
  vision_frame_t frame{};
  frame.camera_id = 2;
  frame.frame_number = 41;
  frame.t_capture = 1.5;
  frame.t_sent = 1.6;
  frame.balls = {{0.75f, 0.5, -0.25, 300, 200, 60}};
  frame.num_balls = 1;
  frame.robots_yellow = {{4, 0.5f, 1.0, 2.0, 0.25, 10, 20}};
  frame.num_robots_yellow = 1;
  frame.robots_blue = {{1, 1.0f, -1.0, -2.0, -0.25, 30, 40}, {2, 0.9f, 3, 1, 0, 0, 0}};
  frame.num_robots_blue = 2;
  const json j = encode_vision_frame(frame);
  EXPECT_EQ(j["camera_id"], 2);
  EXPECT_EQ(j["frame_number"], 41);
  EXPECT_DOUBLE_EQ(j["t_capture"].get<double>(), 1.5);
  EXPECT_DOUBLE_EQ(j["t_sent"].get<double>(), 1.6);
  ASSERT_EQ(j["balls"].size(), 1u);
  EXPECT_DOUBLE_EQ(j["balls"][0]["x"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(j["balls"][0]["confidence"].get<double>(), 0.75);
  ASSERT_EQ(j["yellow"].size(), 1u);
  EXPECT_EQ(j["yellow"][0]["id"], 4);
  EXPECT_DOUBLE_EQ(j["yellow"][0]["orientation"].get<double>(), 0.25);
  ASSERT_EQ(j["blue"].size(), 2u);
  EXPECT_DOUBLE_EQ(j["blue"][0]["y"].get<double>(), -2.0);
  EXPECT_EQ(j["blue"][1]["id"], 2);
}

TEST(ViewerEncoding, RadioPacketNamesModesAndTeam) {
  radio_packet_t packet{};
  packet.team = team_t::BLUE;
  packet.sequence = 99;
  packet.t_sent = 4.25;
  robot_command_t command{};
  command.robot_id = 5;
  command.mode = robot_command_t::MODE_GLOBAL_VELOCITY;
  command.vx = 1.5;
  command.vy = -0.5;
  command.omega = 2;
  command.kick_speed = 4;
  command.num_wheels = 0;
  packet.commands = {command};
  packet.commands.push_back(command);
  packet.commands[1].mode = robot_command_t::MODE_LOCAL_VELOCITY;
  packet.commands.push_back(command);
  packet.commands[2].mode = robot_command_t::MODE_WHEEL_SPEEDS;
  packet.num_commands = 3;
  const json j = encode_radio_packet(packet);
  EXPECT_EQ(j["team"], "blue");
  EXPECT_EQ(j["sequence"], 99);
  EXPECT_DOUBLE_EQ(j["t_sent"].get<double>(), 4.25);
  ASSERT_EQ(j["commands"].size(), 3u);
  EXPECT_EQ(j["commands"][0]["id"], 5);
  EXPECT_EQ(j["commands"][0]["mode"], "global");
  EXPECT_EQ(j["commands"][1]["mode"], "local");
  EXPECT_EQ(j["commands"][2]["mode"], "wheels");
  EXPECT_DOUBLE_EQ(j["commands"][0]["vx"].get<double>(), 1.5);
  EXPECT_DOUBLE_EQ(j["commands"][0]["vy"].get<double>(), -0.5);
  EXPECT_DOUBLE_EQ(j["commands"][0]["omega"].get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(j["commands"][0]["kick"].get<double>(), 4.0);
}

TEST(ViewerEncoding, FieldGeometryAndCameras) {
  vision_geometry_t geometry{};
  geometry.field.name = "division_b";
  geometry.field.field_length = 9;
  geometry.field.field_width = 6;
  geometry.field.goal_width = 1;
  geometry.field.ball_radius = 0.0215;
  geometry.field.boundary_width = 0.3;
  geometry.field.boundary_width_goal_line = 0.6;
  geometry.field.goal_substitution_area_width = 0.25;
  geometry.field.penalty_mark_distance = 6;
  camera_calibration_t camera{};
  camera.camera_id = 1;
  camera.position[0] = -2.25;
  camera.position[2] = 4;
  geometry.cameras = {camera};
  geometry.num_cameras = 1;
  const json field = encode_field_geometry(geometry.field);
  EXPECT_EQ(field["name"], "division_b");
  EXPECT_DOUBLE_EQ(field["field_length"].get<double>(), 9.0);
  EXPECT_DOUBLE_EQ(field["field_width"].get<double>(), 6.0);
  EXPECT_DOUBLE_EQ(field["goal_width"].get<double>(), 1.0);
  EXPECT_NEAR(field["ball_radius"].get<double>(), 0.0215, 1e-12);
  // The page draws the walls behind the goal lines, the substitution areas and the marks.
  EXPECT_DOUBLE_EQ(field["boundary_width"].get<double>(), 0.3);
  EXPECT_DOUBLE_EQ(field["boundary_width_goal_line"].get<double>(), 0.6);
  EXPECT_DOUBLE_EQ(field["goal_substitution_area_width"].get<double>(), 0.25);
  EXPECT_DOUBLE_EQ(field["penalty_mark_distance"].get<double>(), 6.0);
  EXPECT_EQ(field.size(), 18u) << "every field_geometry_t field";
  const json cameras = encode_cameras(geometry);
  ASSERT_EQ(cameras.size(), 1u);
  EXPECT_EQ(cameras[0]["camera_id"], 1);
  EXPECT_DOUBLE_EQ(cameras[0]["x"].get<double>(), -2.25);
  EXPECT_DOUBLE_EQ(cameras[0]["z"].get<double>(), 4.0);
}

referee_t referee_after_goal() {
  referee_t r{};
  r.sim_time = 42.5;
  r.stage = referee_t::STAGE_FIRST_HALF;
  r.stage_time_left = 257.4999;
  r.command = referee_t::STOP;
  r.command_counter = 5;
  r.has_next_command = true;
  r.next_command = referee_t::PREPARE_KICKOFF_BLUE;
  r.ball_in_play = false;
  r.action_time_left = 0;
  r.yellow_score = 1;
  r.blue_score = 0;
  r.yellow_fouls = 2;
  r.blue_fouls = 3;
  r.yellow_goalkeeper = 0;
  r.blue_goalkeeper = 5;
  referee_event_t goal{};
  goal.type = referee_event_t::GOAL;
  goal.has_team = true;
  goal.team = team_t::YELLOW;
  goal.description = "goal by yellow 3";
  r.events = {goal};
  r.num_events = 1;
  return r;
}

TEST(ViewerEncoding, RefereeNamesStageCommandAndEventsAndCarriesTheScore) {
  const json j = encode_referee(referee_after_goal());
  EXPECT_DOUBLE_EQ(j["sim_time"].get<double>(), 42.5);
  EXPECT_EQ(j["stage"], "NORMAL_FIRST_HALF");
  EXPECT_DOUBLE_EQ(j["stage_time_left"].get<double>(), 257.5) << "rounded to 1 ms";
  EXPECT_EQ(j["command"], "STOP");
  EXPECT_EQ(j["command_counter"], 5);
  EXPECT_EQ(j["next_command"], "PREPARE_KICKOFF_BLUE");
  EXPECT_EQ(j["ball_in_play"], false);
  EXPECT_EQ(j["game_over"], false);
  EXPECT_EQ(j["yellow"]["score"], 1);
  EXPECT_EQ(j["blue"]["score"], 0);
  EXPECT_EQ(j["yellow"]["fouls"], 2);
  EXPECT_EQ(j["blue"]["fouls"], 3);
  EXPECT_EQ(j["blue"]["goalkeeper"], 5);
  ASSERT_EQ(j["events"].size(), 1u);
  EXPECT_EQ(j["events"][0]["type"], "GOAL");
  EXPECT_EQ(j["events"][0]["team"], "yellow");
  EXPECT_EQ(j["events"][0]["description"], "goal by yellow 3");
}

TEST(ViewerEncoding, RefereeWithUnknownNumbersNoNextCommandAndManyEvents) {
  referee_t r = referee_after_goal();
  r.stage = 99;
  r.command = -3;
  r.has_next_command = false;
  r.stage_time_left = std::numeric_limits<double>::infinity();
  r.events.assign(1000, r.events[0]);
  r.events.back().has_team = false;
  r.events.back().type = 77;
  r.num_events = 1000;
  const json j = encode_referee(r);
  EXPECT_EQ(j["stage"], "STAGE 99");
  EXPECT_EQ(j["command"], "COMMAND -3");
  EXPECT_TRUE(j["next_command"].is_null());
  EXPECT_TRUE(j["stage_time_left"].is_null());
  ASSERT_EQ(j["events"].size(), 8u) << "only the newest few";
  EXPECT_EQ(j["events"][7]["type"], "EVENT 77");
  EXPECT_TRUE(j["events"][7]["team"].is_null());
  // Every stage and command the message names has its SSL name.
  r.stage = referee_t::STAGE_POST_GAME;
  r.command = referee_t::BALL_PLACEMENT_BLUE;
  EXPECT_EQ(encode_referee(r)["stage"], "POST_GAME");
  EXPECT_EQ(encode_referee(r)["command"], "BALL_PLACEMENT_BLUE");
  // Command names come from referee_t's constants, its STAGE_*s left out
  // (HALT and STAGE_FIRST_HALF_PRE are both 0).
  r.command = referee_t::HALT;
  EXPECT_EQ(encode_referee(r)["command"], "HALT");
  r.command = referee_t::TIMEOUT_YELLOW;
  EXPECT_EQ(encode_referee(r)["command"], "TIMEOUT_YELLOW");
  r.events.back().type = referee_event_t::TOO_MANY_ROBOTS;
  EXPECT_EQ(encode_referee(r)["events"][7]["type"], "TOO_MANY_ROBOTS");
}

// The teams' names, when referee_t has them (HasTeamNames); a template, so that
// this compiles whether it has them or not.
template <typename Referee>
void expect_team_names_shown() {
  if constexpr (HasTeamNames<Referee>::value) {
    Referee r = referee_after_goal();
    r.yellow_name = "TIGERs";
    r.blue_name = "ER-Force";
    const json j = encode_referee(r);
    EXPECT_EQ(j["yellow"]["name"], "TIGERs");
    EXPECT_EQ(j["blue"]["name"], "ER-Force");
  } else {
    EXPECT_FALSE(encode_referee(referee_after_goal())["yellow"].contains("name"));
    GTEST_SKIP() << "referee_t carries no team names in this tree";
  }
}

TEST(ViewerEncoding, RefereeTeamNamesWhenTheMessageHasThem) {
  expect_team_names_shown<referee_t>();
}

TEST(ViewerControl, PauseResumeResetAndSpeed) {
  auto parsed = parse_control_request(R"({"action":"pause"})", 7, "viewer");
  ASSERT_TRUE(parsed.request) << parsed.error;
  EXPECT_EQ(parsed.request->action, +sim_control_t::PAUSE);
  EXPECT_EQ(parsed.request->request_id, 7);
  EXPECT_EQ(parsed.request->sender, "viewer");
  EXPECT_EQ(parsed.request->num_robots, 0);
  EXPECT_FALSE(parsed.request->has_ball);
  EXPECT_EQ(parse_control_request(R"({"action":"resume"})", 1, "v").request->action,
            +sim_control_t::RESUME);
  EXPECT_EQ(parse_control_request(R"({"action":"reset"})", 1, "v").request->action,
            +sim_control_t::RESET);
  parsed = parse_control_request(R"({"action":"speed","factor":0.5})", 1, "v");
  ASSERT_TRUE(parsed.request) << parsed.error;
  EXPECT_EQ(parsed.request->action, +sim_control_t::SET_SPEED);
  EXPECT_DOUBLE_EQ(parsed.request->speed_factor, 0.5);
  EXPECT_TRUE(parse_control_request(R"({"action":"speed","factor":0})", 1, "v").request)
      << "0 = as fast as possible";
}

TEST(ViewerControl, PlaceBallAndRobot) {
  auto parsed = parse_control_request(R"({"action":"place_ball","x":1.5,"y":-0.5})", 3, "viewer");
  ASSERT_TRUE(parsed.request) << parsed.error;
  EXPECT_EQ(parsed.request->action, +sim_control_t::PLACE);
  EXPECT_TRUE(parsed.request->has_ball);
  EXPECT_DOUBLE_EQ(parsed.request->ball.position[0], 1.5);
  EXPECT_DOUBLE_EQ(parsed.request->ball.position[1], -0.5);
  EXPECT_DOUBLE_EQ(parsed.request->ball.position[2], 0.0) << "resting on the ground";
  EXPECT_DOUBLE_EQ(parsed.request->ball.linear_velocity[0], 0.0);
  EXPECT_EQ(parsed.request->num_robots, 0);

  parsed = parse_control_request(
      R"({"action":"place_robot","team":"blue","id":4,"x":-2,"y":1,"orientation":1.25})", 4, "v");
  ASSERT_TRUE(parsed.request) << parsed.error;
  EXPECT_EQ(parsed.request->action, +sim_control_t::PLACE);
  EXPECT_FALSE(parsed.request->has_ball);
  ASSERT_EQ(parsed.request->num_robots, 1);
  ASSERT_EQ(parsed.request->robots.size(), 1u);
  const auto& robot = parsed.request->robots[0];
  EXPECT_EQ(robot.team, +team_t::BLUE);
  EXPECT_EQ(robot.robot_id, 4);
  EXPECT_TRUE(robot.present);
  EXPECT_EQ(robot.robot_type, "") << "keep the robot's type";
  EXPECT_DOUBLE_EQ(robot.x, -2.0);
  EXPECT_DOUBLE_EQ(robot.y, 1.0);
  EXPECT_DOUBLE_EQ(robot.orientation, 1.25);
}

TEST(ViewerControl, BadRequestsAreRefusedWithAReason) {
  for (const char* text :
       {"", "not json", "[1,2]", R"({"no":"action"})", R"({"action":5})", R"({"action":"explode"})",
        R"({"action":"speed"})", R"({"action":"speed","factor":-1})",
        R"({"action":"speed","factor":1000})", R"({"action":"speed","factor":"fast"})",
        R"({"action":"place_ball","x":1})", R"({"action":"place_ball","x":1,"y":1e300})",
        R"({"action":"place_ball","x":null,"y":0})",
        R"({"action":"place_robot","team":"red","id":1,"x":0,"y":0})",
        R"({"action":"place_robot","team":"blue","id":-1,"x":0,"y":0})",
        R"({"action":"place_robot","team":"blue","id":1.5,"x":0,"y":0})",
        R"({"action":"place_robot","team":"blue","id":1,"x":0})",
        R"({"action":"place_robot","team":"blue","id":1,"x":0,"y":0,"orientation":"up"})"}) {
    const auto parsed = parse_control_request(text, 1, "viewer");
    EXPECT_FALSE(parsed.request) << text;
    EXPECT_FALSE(parsed.error.empty()) << text;
  }
}

TEST(ViewerModelTest, SnapshotHoldsOnlyTheNewestStateAndTheNewestFramePerCamera) {
  ViewerModel model;
  const auto t0 = ViewerModel::Clock::now();
  for (int i = 1; i <= 100; ++i) model.on_sim_state(two_robot_state(i * 0.01), t0);
  vision_frame_t frame{};
  for (int camera = 0; camera < 2; ++camera) {
    for (int n = 0; n < 5; ++n) {
      frame.camera_id = camera;
      frame.frame_number = n;
      model.on_vision(frame, t0);
    }
  }
  EXPECT_TRUE(model.changed());
  const json snapshot = json::parse(model.snapshot(t0, {{"clients", 1}}));
  EXPECT_FALSE(model.changed());
  EXPECT_EQ(snapshot["type"], "frame");
  EXPECT_DOUBLE_EQ(snapshot["state"]["sim_time"].get<double>(), 1.0) << "only the newest state";
  ASSERT_EQ(snapshot["vision"].size(), 2u) << "one frame per camera";
  EXPECT_EQ(snapshot["vision"][0]["camera_id"], 0);
  EXPECT_EQ(snapshot["vision"][0]["frame_number"], 4);
  EXPECT_EQ(snapshot["vision"][1]["frame_number"], 4);
  EXPECT_TRUE(snapshot["geometry"].is_null());
  EXPECT_EQ(snapshot["server"]["clients"], 1);
}

TEST(ViewerModelTest, VisionGeometryWinsOverPhysicsGeometryAndResetForgetsOldDetections) {
  ViewerModel model;
  const auto t0 = ViewerModel::Clock::now();
  field_geometry_t physics_field{};
  physics_field.name = "from_physics";
  model.on_sim_geometry(physics_field, t0);
  EXPECT_EQ(json::parse(model.snapshot(t0, {}))["geometry"]["name"], "from_physics");
  vision_geometry_t vision{};
  vision.field.name = "from_vision";
  model.on_vision_geometry(vision, t0);
  model.on_sim_geometry(physics_field, t0);
  EXPECT_EQ(json::parse(model.snapshot(t0, {}))["geometry"]["name"], "from_vision");

  radio_packet_t packet{};
  packet.team = team_t::YELLOW;
  model.on_radio(0, packet, t0);
  model.on_sim_state(two_robot_state(5), t0);
  model.on_vision(vision_frame_t{}, t0);
  json snapshot = json::parse(model.snapshot(t0, {}));
  EXPECT_EQ(snapshot["vision"].size(), 1u);
  EXPECT_EQ(snapshot["commands"]["yellow"]["team"], "yellow");
  EXPECT_TRUE(snapshot["commands"]["blue"].is_null());
  model.on_sim_state(two_robot_state(0.01), t0);  // time went back: a reset
  snapshot = json::parse(model.snapshot(t0, {}));
  EXPECT_EQ(snapshot["vision"].size(), 0u);
  EXPECT_TRUE(snapshot["commands"]["yellow"].is_null());
}

TEST(ViewerModelTest, SnapshotHoldsTheNewestRefereeStateAndItsRate) {
  ViewerModel model;
  const auto t0 = ViewerModel::Clock::now();
  EXPECT_TRUE(json::parse(model.snapshot(t0, {}))["referee"].is_null()) << "none before any";
  referee_t r = referee_after_goal();
  for (int i = 0; i < 10; ++i) {
    r.blue_score = i;
    model.on_referee(r, t0 + std::chrono::milliseconds(i * 100));
  }
  EXPECT_TRUE(model.changed());
  const json snapshot = json::parse(model.snapshot(t0 + std::chrono::seconds(1), {}));
  EXPECT_EQ(snapshot["referee"]["blue"]["score"], 9) << "only the newest";
  EXPECT_NEAR(snapshot["rates"]["REFEREE"].get<double>(), 10, 1) << snapshot["rates"].dump();
}

TEST(ViewerModelTest, RatesPerChannelUseTheActualChannelNames) {
  ViewerModel model;
  model.set_channel_names({{"SIM_STATE", "SIM2_SIM_STATE"}});
  const auto t0 = ViewerModel::Clock::now();
  // 240 states spread over one second, then a snapshot a second later.
  for (int i = 0; i < 240; ++i) {
    model.on_sim_state(two_robot_state(i / 240.0), t0 + std::chrono::microseconds(i * 4166));
  }
  const json rates = json::parse(model.snapshot(t0 + std::chrono::seconds(1), {}))["rates"];
  EXPECT_NEAR(rates["SIM2_SIM_STATE"].get<double>(), 240, 1) << rates.dump();
  EXPECT_FALSE(rates.contains("SIM_STATE"));
  EXPECT_DOUBLE_EQ(rates["VISION"].get<double>(), 0.0);
}

// LCM strings are bytes: a robot type, field name or ack message that is not
// UTF-8 made nlohmann's dump() throw, and the viewer stopped (fuzz_lcm_consumers).
TEST(ViewerModelTest, StringsThatAreNotUtf8DoNotStopTheSnapshot) {
  ViewerModel model;
  const auto t0 = ViewerModel::Clock::now();
  sim_state_t state = two_robot_state(1);
  state.robots[0].robot_type = "omni\xff\xfe";
  model.on_sim_state(state, t0);
  field_geometry_t field{};
  field.name = "div\xc3";
  model.on_sim_geometry(field, t0);
  sim_control_ack_t ack{};
  ack.message = "\x80ok";
  model.on_ack(ack);
  referee_t referee = referee_after_goal();
  referee.events[0].description = "goal\xff";
  model.on_referee(referee, t0);
  std::string text;
  ASSERT_NO_THROW(text = model.snapshot(t0, {}));
  const json snapshot = json::parse(text);
  EXPECT_EQ(snapshot["state"]["robots"][0]["type"], "omni\xef\xbf\xbd\xef\xbf\xbd")
      << "each bad byte becomes U+FFFD";
  EXPECT_EQ(snapshot["geometry"]["name"], "div\xef\xbf\xbd");
  EXPECT_EQ(snapshot["ack"]["message"], "\xef\xbf\xbdok");
  EXPECT_EQ(snapshot["referee"]["events"][0]["description"], "goal\xef\xbf\xbd");
  EXPECT_EQ(snapshot["state"]["robots"][1]["type"], "omni4_ssl");
}

TEST(RateMeterTest, CountsPerWindowAndFallsToZeroWhenQuiet) {
  RateMeter meter;
  const auto t0 = RateMeter::Clock::now();
  for (int i = 0; i < 30; ++i) meter.count(t0 + std::chrono::milliseconds(i * 33));
  EXPECT_NEAR(meter.rate(t0 + std::chrono::milliseconds(1000)), 30, 0.5);
  EXPECT_DOUBLE_EQ(meter.rate(t0 + std::chrono::milliseconds(2100)), 0.0);
}

}  // namespace
}  // namespace ubersim::viewer
