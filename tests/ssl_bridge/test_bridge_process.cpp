// The real ubersim_ssl_bridge process, driven from both sides: synthetic
// VISION / VISION_GEOMETRY / RADIO_FEEDBACK messages on real LCM, and a client
// written against the published SSL protocols (generated protobuf classes,
// raw UDP on loopback). ISOLATED: its own network namespace, default ports.
#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>
#include <ssl_gc_referee_message.pb.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <thread>
#include <ubersim/radio_feedback_t.hpp>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/referee_t.hpp>
#include <ubersim/robot_command_t.hpp>
#include <ubersim/team_t.hpp>
#include <ubersim/vision_cameras_t.hpp>
#include <ubersim/vision_frame_t.hpp>
#include <ubersim/vision_geometry_t.hpp>

#include "child_process.hpp"
#include "ssl_client.hpp"
#include "ubersim/common_options.hpp"
#include "ubersim/message_bus.hpp"

namespace {

using ubersim::test::ChildProcess;

ubersim::vision_frame_t sample_frame(int64_t number) {
  ubersim::vision_frame_t f{};
  f.camera_id = 2;
  f.frame_number = number;
  f.t_capture = 10.0 + 0.033 * static_cast<double>(number);
  f.t_sent = f.t_capture + 0.004;
  ubersim::vision_ball_t ball{};
  ball.confidence = 0.9f;
  ball.x = 1.2345;
  ball.y = -0.678;
  ball.pixel_x = 401.25;
  ball.pixel_y = 99.5;
  f.balls = {ball, ball};
  f.balls[1].x = -3.9;
  f.balls[1].confidence = 0.2f;
  f.num_balls = 2;
  for (int i = 0; i < 3; ++i) {
    ubersim::vision_robot_t r{};
    r.robot_id = 10 + i;
    r.confidence = 0.5f + 0.1f * static_cast<float>(i);
    r.x = -2.0 + 0.75 * i;
    r.y = 1.1 - 0.3 * i;
    r.orientation = -3.0 + 1.7 * i;
    r.pixel_x = 100.125 + i;
    r.pixel_y = 200.75 - i;
    (i < 2 ? f.robots_yellow : f.robots_blue).push_back(r);
  }
  f.num_robots_yellow = 2;
  f.num_robots_blue = 1;
  return f;
}

void expect_robot(const ubersim::vision_robot_t& in, const SSL_DetectionRobot& out) {
  EXPECT_EQ(out.robot_id(), static_cast<uint32_t>(in.robot_id));
  EXPECT_FLOAT_EQ(out.confidence(), in.confidence);
  EXPECT_FLOAT_EQ(out.x(), static_cast<float>(in.x * 1000.0));
  EXPECT_FLOAT_EQ(out.y(), static_cast<float>(in.y * 1000.0));
  EXPECT_FLOAT_EQ(out.orientation(), static_cast<float>(in.orientation));
  EXPECT_FLOAT_EQ(out.pixel_x(), static_cast<float>(in.pixel_x));
  EXPECT_FLOAT_EQ(out.pixel_y(), static_cast<float>(in.pixel_y));
}

class SslBridgeProcess : public ::testing::Test {
 protected:
  void SetUp() override {
    std::vector<std::string> argv{UBERSIM_SSL_BRIDGE_EXE, "--ack-timeout", "0.3"};
    for (const std::string& option : ports_.bridge_options()) argv.push_back(option);
    for (const std::string& option : extra_options()) argv.push_back(option);
    bridge_ = std::make_unique<ChildProcess>(argv, ::testing::TempDir() + "ssl_bridge_process.log");
    ASSERT_TRUE(bridge_->wait_for_output("vision to", 10)) << bridge_->log();
    bus_.subscribe<ubersim::radio_packet_t>(
        "RADIO_BLUE", [this](const ubersim::radio_packet_t& p) { radio_blue_.push_back(p); });
  }
  void TearDown() override {
    if (bridge_) {
      EXPECT_EQ(bridge_->stop(10), 0) << bridge_->log();
    }
  }

  virtual std::vector<std::string> extra_options() const { return {}; }

  // Publishes on LCM until the bridge's packet arrives (it may still be subscribing).
  template <class Msg>
  std::optional<SSL_WrapperPacket> publish_until_seen(
      const std::string& channel, const Msg& message,
      const std::function<bool(const SSL_WrapperPacket&)>& is_it) {
    for (int attempt = 0; attempt < 50; ++attempt) {
      bus_.publish(channel, message);
      std::optional<SSL_WrapperPacket> seen;
      if (vision_.receive_until(
              [&](const SSL_WrapperPacket& p) {
                if (!is_it(p)) return false;
                seen = p;
                return true;
              },
              0.2)) {
        return seen;
      }
    }
    return std::nullopt;
  }

  bool wait_for_radio(size_t count, double timeout_s) {
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (radio_blue_.size() < count && std::chrono::steady_clock::now() < deadline) {
      bus_.wait_and_handle(20);
    }
    return radio_blue_.size() >= count;
  }

  const ssl_test::TestPorts ports_ = ssl_test::TestPorts::from_environment();
  ssl_test::VisionReceiver vision_{"224.5.23.2", ports_.vision};
  ubersim::MessageBus bus_{ubersim::with_receive_buffer(ubersim::default_lcm_url())};
  std::unique_ptr<ChildProcess> bridge_;
  std::vector<ubersim::radio_packet_t> radio_blue_;
};

}  // namespace

TEST_F(SslBridgeProcess, DetectionsMatchTheVisionFramesFieldByField) {
  for (int64_t number : {7, 8, 9}) {
    const ubersim::vision_frame_t frame = sample_frame(number);
    const auto packet = publish_until_seen("VISION", frame, [&](const SSL_WrapperPacket& p) {
      return p.has_detection() && p.detection().frame_number() == static_cast<uint32_t>(number);
    });
    ASSERT_TRUE(packet.has_value()) << bridge_->log();
    const SSL_DetectionFrame& d = packet->detection();
    EXPECT_FALSE(packet->has_geometry());
    EXPECT_EQ(d.camera_id(), 2u);
    EXPECT_DOUBLE_EQ(d.t_capture(), frame.t_capture);
    EXPECT_DOUBLE_EQ(d.t_sent(), frame.t_sent);
    ASSERT_EQ(d.balls_size(), 2);
    for (int i = 0; i < 2; ++i) {
      const auto& in = frame.balls[static_cast<size_t>(i)];
      EXPECT_FLOAT_EQ(d.balls(i).confidence(), in.confidence);
      EXPECT_FLOAT_EQ(d.balls(i).x(), static_cast<float>(in.x * 1000.0));
      EXPECT_FLOAT_EQ(d.balls(i).y(), static_cast<float>(in.y * 1000.0));
      EXPECT_FLOAT_EQ(d.balls(i).pixel_x(), static_cast<float>(in.pixel_x));
      EXPECT_FLOAT_EQ(d.balls(i).pixel_y(), static_cast<float>(in.pixel_y));
    }
    ASSERT_EQ(d.robots_yellow_size(), 2);
    ASSERT_EQ(d.robots_blue_size(), 1);
    expect_robot(frame.robots_yellow[0], d.robots_yellow(0));
    expect_robot(frame.robots_yellow[1], d.robots_yellow(1));
    expect_robot(frame.robots_blue[0], d.robots_blue(0));
  }
  EXPECT_EQ(vision_.undecodable(), 0);
}

TEST_F(SslBridgeProcess, GeometryPacketCarriesFieldCamerasAndBallModel) {
  ubersim::vision_geometry_t g{};
  g.field.name = "division_b";
  g.field.field_length = 9.0;
  g.field.field_width = 6.0;
  g.field.goal_width = 1.0;
  g.field.goal_depth = 0.18;
  g.field.boundary_width = 0.3;
  g.field.line_width = 0.01;
  g.field.center_circle_radius = 0.5;
  g.field.penalty_area_depth = 1.0;
  g.field.penalty_area_width = 2.0;
  g.field.ball_radius = 0.0215;
  ubersim::camera_calibration_t camera{};
  camera.camera_id = 0;
  camera.focal_length = 650;
  camera.image_width = 780;
  camera.image_height = 580;
  camera.position[2] = 4.0;
  camera.orientation[1] = 1;  // looking down
  g.cameras = {camera, camera};
  g.cameras[1].camera_id = 1;
  g.num_cameras = 2;
  const auto packet = publish_until_seen(
      "VISION_GEOMETRY", g, [](const SSL_WrapperPacket& p) { return p.has_geometry(); });
  ASSERT_TRUE(packet.has_value()) << bridge_->log();
  const SSL_GeometryData& geometry = packet->geometry();
  EXPECT_EQ(geometry.field().field_length(), 9000);
  EXPECT_EQ(geometry.field().field_width(), 6000);
  EXPECT_EQ(geometry.field().goal_depth(), 180);
  EXPECT_FLOAT_EQ(geometry.field().ball_radius(), 21.5f);
  EXPECT_FLOAT_EQ(geometry.field().max_robot_radius(), 90.0f);  // omni4_ssl
  EXPECT_EQ(geometry.field().field_lines_size(), 12);
  ASSERT_EQ(geometry.calib_size(), 2);
  EXPECT_EQ(geometry.calib(1).camera_id(), 1u);
  EXPECT_FLOAT_EQ(geometry.calib(0).focal_length(), 650.0f);
  EXPECT_FLOAT_EQ(geometry.calib(0).derived_camera_world_tz(), 4000.0f);
  // The shipped ball config's model (config/balls/ssl_golf_ball.cfg).
  ASSERT_TRUE(geometry.models().has_straight_two_phase());
  EXPECT_DOUBLE_EQ(geometry.models().straight_two_phase().acc_slide(), -3.6);
  EXPECT_DOUBLE_EQ(geometry.models().straight_two_phase().acc_roll(), -0.3);
  EXPECT_DOUBLE_EQ(geometry.models().straight_two_phase().k_switch(), 0.7);
}

TEST_F(SslBridgeProcess, RobotCommandsBecomeRadioPacketsWithExactUnits) {
  ssl_test::UdpClient blue(ports_.blue);
  RobotControl control;
  RobotCommand* c = control.add_robot_commands();
  c->set_id(3);
  MoveLocalVelocity* v = c->mutable_move_command()->mutable_local_velocity();
  v->set_forward(1.0f);
  v->set_left(-0.5f);
  v->set_angular(2.0f);
  c->set_kick_speed(4.0f);
  c->set_kick_angle(30.0f);
  c->set_dribbler_speed(600.0f);
  const auto response = ssl_test::control(blue, control);
  ASSERT_TRUE(response.has_value()) << bridge_->log();
  EXPECT_EQ(response->errors_size(), 0);
  ASSERT_TRUE(wait_for_radio(1, 5)) << bridge_->log();
  const ubersim::radio_packet_t& packet = radio_blue_.back();
  EXPECT_EQ(packet.team, +ubersim::team_t::BLUE);
  ASSERT_EQ(packet.num_commands, 1);
  const ubersim::robot_command_t& r = packet.commands[0];
  EXPECT_EQ(r.robot_id, 3);
  EXPECT_EQ(r.mode, +ubersim::robot_command_t::MODE_LOCAL_VELOCITY);
  EXPECT_DOUBLE_EQ(r.vx, 1.0);
  EXPECT_DOUBLE_EQ(r.vy, -0.5);
  EXPECT_DOUBLE_EQ(r.omega, 2.0);
  EXPECT_DOUBLE_EQ(r.kick_speed, 0.0);
  EXPECT_DOUBLE_EQ(r.chip_speed, 4.0);
  EXPECT_DOUBLE_EQ(r.chip_angle, M_PI / 6);
  EXPECT_DOUBLE_EQ(r.dribbler_speed, 20 * M_PI);
}

TEST_F(SslBridgeProcess, RobotControlResponseCarriesTheLatestFeedback) {
  ubersim::radio_feedback_t feedback{};
  feedback.team = ubersim::team_t::YELLOW;
  ubersim::robot_feedback_t a{};
  a.robot_id = 1;
  a.ball_contact = true;
  ubersim::robot_feedback_t b{};
  b.robot_id = 2;
  feedback.robots = {a, b};
  feedback.num_robots = 2;
  ssl_test::UdpClient yellow(ports_.yellow);
  RobotControl control;
  control.add_robot_commands()->set_id(1);
  std::optional<RobotControlResponse> response;
  for (int attempt = 0; attempt < 50; ++attempt) {
    bus_.publish("RADIO_FEEDBACK_YELLOW", feedback);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    response = ssl_test::control(yellow, control);
    if (response && response->feedback_size() > 0) break;
  }
  ASSERT_TRUE(response.has_value());
  ASSERT_EQ(response->feedback_size(), 2) << bridge_->log();
  EXPECT_EQ(response->feedback(0).id(), 1u);
  EXPECT_TRUE(response->feedback(0).dribbler_ball_contact());
  EXPECT_EQ(response->feedback(1).id(), 2u);
  EXPECT_FALSE(response->feedback(1).dribbler_ball_contact());
}

TEST_F(SslBridgeProcess, GarbageIsAnsweredWithAnErrorAndTheBridgeKeepsRunning) {
  ssl_test::UdpClient control_port(ports_.control);
  ssl_test::UdpClient blue(ports_.blue);
  // Truncated: field 1, length-delimited, length varint never ends.
  const std::string garbage("\x0a\xff\xff\xff", 4);
  for (int round = 0; round < 3; ++round) {
    control_port.send(garbage);
    const auto bytes = control_port.receive(3);
    ASSERT_TRUE(bytes.has_value()) << bridge_->log();
    SimulatorResponse response;
    ASSERT_TRUE(response.ParseFromString(*bytes));
    ASSERT_EQ(response.errors_size(), 1);
    EXPECT_EQ(response.errors(0).code(), "UBERSIM_MALFORMED");

    blue.send(garbage);
    const auto robot_bytes = blue.receive(3);
    ASSERT_TRUE(robot_bytes.has_value());
    RobotControlResponse robot_response;
    ASSERT_TRUE(robot_response.ParseFromString(*robot_bytes));
    ASSERT_GE(robot_response.errors_size(), 1);
    EXPECT_EQ(robot_response.errors(0).code(), "UBERSIM_MALFORMED");
  }
  // Bytes that decode, but as fields the protocol does not have.
  blue.send(std::string("\xa0\x06\x01", 3));  // field 100, varint 1
  const auto unknown = blue.receive(3);
  ASSERT_TRUE(unknown.has_value());
  RobotControlResponse unknown_response;
  ASSERT_TRUE(unknown_response.ParseFromString(*unknown));
  ASSERT_EQ(unknown_response.errors_size(), 1);
  EXPECT_EQ(unknown_response.errors(0).code(), "UBERSIM_UNKNOWN_FIELDS");
  // Random datagrams (fixed seed): each one is answered, none crashes the bridge.
  std::mt19937 random(12345);
  for (int i = 0; i < 300; ++i) {
    std::string bytes(static_cast<size_t>(random() % 200), '\0');
    for (char& byte : bytes) byte = static_cast<char>(random() & 0xff);
    ssl_test::UdpClient& port = (i % 2 == 0) ? control_port : blue;
    port.send(bytes);
    ASSERT_TRUE(port.receive(3).has_value()) << "datagram " << i << " not answered";
  }
  EXPECT_TRUE(bridge_->running());
  // Still working: a valid command goes through.
  RobotControl control;
  control.add_robot_commands()->set_id(6);
  const auto response = ssl_test::control(blue, control);
  ASSERT_TRUE(response.has_value());
  EXPECT_EQ(response->errors_size(), 0);
  // (Some random datagrams decode as commands too; look for this one.)
  const auto has_robot_6 = [this] {
    for (const auto& packet : radio_blue_) {
      for (const auto& command : packet.commands) {
        if (command.robot_id == 6) return true;
      }
    }
    return false;
  };
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (!has_robot_6() && std::chrono::steady_clock::now() < deadline) bus_.wait_and_handle(20);
  EXPECT_TRUE(has_robot_6());
}

TEST_F(SslBridgeProcess, UnsupportedAndUnansweredControlIsNeverSilent) {
  ssl_test::UdpClient control_port(ports_.control);
  // A realism config of a type ubersim does not know: answered at once.
  SimulatorCommand specs;
  google::protobuf::Any* other = specs.mutable_config()->mutable_realism_config()->add_custom();
  other->set_type_url("type.googleapis.com/SomeOtherSimulatorsRealism");
  auto response = ssl_test::command(control_port, specs);
  ASSERT_TRUE(response.has_value());
  ASSERT_EQ(response->errors_size(), 1);
  EXPECT_EQ(response->errors(0).code(), "UBERSIM_UNSUPPORTED");
  // No physics in this test: the teleport is forwarded, and answered once the
  // acknowledgement timeout passes.
  SimulatorCommand teleport;
  teleport.mutable_control()->mutable_teleport_ball()->set_x(1);
  teleport.mutable_control()->mutable_teleport_ball()->set_y(1);
  response = ssl_test::command(control_port, teleport);
  ASSERT_TRUE(response.has_value());
  ASSERT_EQ(response->errors_size(), 1);
  EXPECT_EQ(response->errors(0).code(), "UBERSIM_NO_ANSWER");
}

// The official simulation controller's Division A geometry: its camera
// calibrations go out on VISION_CAMERAS, and no error names them.
TEST_F(SslBridgeProcess, CameraCalibrationsOfAGeometryGoOutOnVisionCameras) {
  std::vector<ubersim::vision_cameras_t> sets;
  bus_.subscribe<ubersim::vision_cameras_t>(
      "VISION_CAMERAS", [&](const ubersim::vision_cameras_t& s) { sets.push_back(s); });
  std::ifstream file(UBERSIM_OFFICIAL_GEOMETRY_DIV_A);
  std::stringstream text;
  text << file.rdbuf();
  SimulatorCommand command;
  ASSERT_TRUE(google::protobuf::TextFormat::ParseFromString(
      text.str(), command.mutable_config()->mutable_geometry()));
  ssl_test::UdpClient control_port(ports_.control);
  const auto response = ssl_test::command(control_port, command);
  ASSERT_TRUE(response.has_value());
  for (const auto& error : response->errors()) {  // no physics here: the field is not answered
    EXPECT_EQ(error.message().find("calib"), std::string::npos) << error.message();
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  while (sets.empty() && std::chrono::steady_clock::now() < deadline) bus_.wait_and_handle(20);
  ASSERT_EQ(sets.size(), 1u);
  ASSERT_EQ(sets[0].num_cameras, 2);
  EXPECT_NEAR(sets[0].cameras[0].position[0], -3.01, 1e-6);
  EXPECT_NEAR(sets[0].cameras[1].position[0], 3.01, 1e-6);
  EXPECT_NEAR(sets[0].cameras[1].position[2], 6.0, 1e-6);
  EXPECT_EQ(sets[0].sender, "ubersim_ssl_bridge");
}

TEST(SslBridgeOptions, DefaultsAreTheLeagueConventions) {
  ChildProcess help({UBERSIM_SSL_BRIDGE_EXE, "--help"}, ::testing::TempDir() + "ssl_help.log");
  EXPECT_EQ(help.wait(10), 0);
  const std::string text = help.log();
  for (const char* expected :
       {"224.5.23.2", "10020", "10300", "10301", "10302", "127.0.0.1", "224.5.23.1", "10003"}) {
    EXPECT_NE(text.find(expected), std::string::npos) << expected << " missing in\n" << text;
  }
}

TEST_F(SslBridgeProcess, RefereeGoesOutAsTheGameControllersMessage) {
  ssl_test::VisionReceiver referee_receiver("224.5.23.1", ports_.referee);
  ubersim::referee_t r{};
  r.stage = ubersim::referee_t::STAGE_FIRST_HALF;
  r.command = ubersim::referee_t::DIRECT_FREE_YELLOW;
  r.command_counter = 5;
  r.yellow_score = 3;
  r.stage_time_left = 100.5;
  r.sim_time = 12.5;
  r.command_time = 11.0;
  r.yellow_name = "Yellow";
  r.blue_name = "Blue";
  ubersim::referee_event_t goal{};
  goal.type = ubersim::referee_event_t::GOAL;
  goal.has_team = true;
  goal.team = ubersim::team_t::BLUE;
  goal.robot_id = 1;
  r.events.push_back(goal);
  r.num_events = 1;
  std::optional<Referee> seen;
  for (int attempt = 0; attempt < 50 && !seen; ++attempt) {
    bus_.publish("REFEREE", r);
    if (auto bytes = referee_receiver.receive_bytes(0.2)) {
      Referee m;
      ASSERT_TRUE(m.ParseFromString(*bytes));
      seen = m;
    }
  }
  ASSERT_TRUE(seen) << bridge_->log();
  EXPECT_EQ(seen->command(), Referee::DIRECT_FREE_YELLOW);
  EXPECT_EQ(seen->stage(), Referee::NORMAL_FIRST_HALF);
  EXPECT_EQ(seen->command_counter(), 5u);
  EXPECT_EQ(seen->yellow().score(), 3u);
  EXPECT_EQ(seen->stage_time_left(), 100'500'000);
  ASSERT_EQ(seen->game_events_size(), 1);
  EXPECT_EQ(seen->game_events(0).goal().by_team(), ::BLUE);
  // One time base with vision's t_capture: sim time (docs/ssl_bridge.md, "Time stamps").
  EXPECT_EQ(seen->packet_timestamp(), 12'500'000u);
  EXPECT_EQ(seen->command_timestamp(), 11'000'000u);
  EXPECT_EQ(seen->yellow().name(), "Yellow");
  EXPECT_EQ(seen->blue().name(), "Blue");
}

TEST_F(SslBridgeProcess, ExitsZeroOnSigint) {
  EXPECT_EQ(bridge_->stop(10, 2 /* SIGINT */), 0) << bridge_->log();
  EXPECT_NE(bridge_->log().find("summary:"), std::string::npos);
  bridge_.reset();
}

namespace {

// What the official game controller sends: a Referee of another source.
std::string game_controller_referee(Referee::Command command, std::uint32_t counter) {
  Referee r;
  r.set_source_identifier("official-game-controller");
  r.set_packet_timestamp(1);
  r.set_stage(Referee::NORMAL_FIRST_HALF_PRE);
  r.set_command(command);
  r.set_command_counter(counter);
  r.set_command_timestamp(1);
  for (Referee::TeamInfo* team : {r.mutable_yellow(), r.mutable_blue()}) {
    team->set_name("ER-Force");
    team->set_score(1);
    team->set_red_cards(0);
    team->set_yellow_cards(0);
    team->set_timeouts(4);
    team->set_timeout_time(300'000'000);
    team->set_goalkeeper(2);
  }
  r.mutable_designated_position()->set_x(-1200);
  r.mutable_designated_position()->set_y(300);
  return r.SerializeAsString();
}

// Our own Referee packets on the group, over `seconds` (the game controller's are not ours).
int ubersim_referee_packets(ssl_test::VisionReceiver& receiver, double seconds) {
  int ours = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < deadline) {
    if (auto bytes = receiver.receive_bytes(0.05)) {
      Referee m;
      if (m.ParseFromString(*bytes) && m.source_identifier().rfind("ubersim-", 0) == 0) ++ours;
    }
  }
  return ours;
}

class SslBridgeOfficialReferee : public SslBridgeProcess {
 protected:
  std::vector<std::string> extra_options() const override { return {"--official-referee"}; }
};

}  // namespace

TEST_F(SslBridgeOfficialReferee, TheGameControllersRefereeGoesToRefereeAndNothingOfOursOut) {
  std::vector<ubersim::referee_t> seen;
  bus_.subscribe<ubersim::referee_t>("REFEREE",
                                     [&](const ubersim::referee_t& r) { seen.push_back(r); });
  for (int attempt = 0; attempt < 50 && seen.empty(); ++attempt) {
    ssl_test::send_to_group("224.5.23.1", ports_.referee,
                            game_controller_referee(Referee::BALL_PLACEMENT_BLUE, 3));
    bus_.wait_and_handle(100);
  }
  ASSERT_FALSE(seen.empty()) << bridge_->log();
  EXPECT_EQ(seen.back().command, +ubersim::referee_t::BALL_PLACEMENT_BLUE);
  EXPECT_EQ(seen.back().stage, +ubersim::referee_t::STAGE_FIRST_HALF_PRE);
  EXPECT_EQ(seen.back().command_counter, 3);
  EXPECT_EQ(seen.back().yellow_goalkeeper, 2);
  ASSERT_TRUE(seen.back().has_designated_position);
  EXPECT_DOUBLE_EQ(seen.back().designated_position[0], -1.2);
  // ubersim's own referee, if one ran, must not reach the group.
  ssl_test::VisionReceiver referee_receiver("224.5.23.1", ports_.referee);
  ubersim::referee_t ours{};
  ours.command = ubersim::referee_t::STOP;
  for (int i = 0; i < 5; ++i) bus_.publish("REFEREE", ours);
  EXPECT_EQ(ubersim_referee_packets(referee_receiver, 1.0), 0);
}

TEST_F(SslBridgeProcess, AnotherGameControllerOnTheGroupStopsOursBeingSent) {
  ssl_test::VisionReceiver referee_receiver("224.5.23.1", ports_.referee);
  ubersim::referee_t ours{};
  ours.command = ubersim::referee_t::STOP;
  int sent_before = 0;
  for (int attempt = 0; attempt < 50 && sent_before == 0; ++attempt) {
    bus_.publish("REFEREE", ours);
    sent_before = ubersim_referee_packets(referee_receiver, 0.1);
  }
  ASSERT_GT(sent_before, 0) << bridge_->log();
  ssl_test::send_to_group("224.5.23.1", ports_.referee, game_controller_referee(Referee::HALT, 1));
  ASSERT_TRUE(bridge_->wait_for_output("another game controller", 5)) << bridge_->log();
  for (int i = 0; i < 5; ++i) bus_.publish("REFEREE", ours);
  EXPECT_EQ(ubersim_referee_packets(referee_receiver, 1.0), 0) << bridge_->log();
}
