// The bridge in front of the real simulation: ubersim_physics (real time),
// ubersim_vision and ubersim_radio as processes over real LCM, driven only
// through the SSL protocols by a client that knows nothing of ubersim:
// teleports show up in the next vision frames, robot commands move robots
// (through the radio emulator), and the responses carry robot feedback.
// ISOLATED: own network namespace, so the league's default ports are free.
#include <grSim_Packet.pb.h>
#include <grSim_Robotstatus.pb.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "child_process.hpp"
#include "grsim_packet.hpp"
#include "ssl_client.hpp"

namespace {

using ubersim::test::ChildProcess;
using Clock = std::chrono::steady_clock;

const SSL_DetectionRobot* find_blue(const SSL_WrapperPacket& packet, uint32_t id) {
  if (!packet.has_detection()) return nullptr;
  for (const auto& robot : packet.detection().robots_blue()) {
    if (robot.robot_id() == id) return &robot;
  }
  return nullptr;
}

TeleportRobot* teleport_blue(SimulatorCommand& command, uint32_t id, float x, float y) {
  TeleportRobot* robot = command.mutable_control()->add_teleport_robot();
  robot->mutable_id()->set_id(id);
  robot->mutable_id()->set_team(BLUE);
  robot->set_x(x);
  robot->set_y(y);
  robot->set_orientation(0);
  return robot;
}

std::string describe(const SimulatorResponse& response) {
  std::string text;
  for (const auto& e : response.errors()) text += e.code() + ": " + e.message() + "\n";
  return text;
}

class SslBridgeSimulation : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string logs = ::testing::TempDir();
    const std::string src = UBERSIM_SOURCE_DIR;
    vision_ = std::make_unique<ChildProcess>(
        std::vector<std::string>{UBERSIM_VISION_EXE, "--profile", "cmdragons02", "--seed", "3"},
        logs + "ssl_sim_vision.log");
    radio_ = std::make_unique<ChildProcess>(
        std::vector<std::string>{UBERSIM_RADIO_EXE, "--profile",
                                 src + "/tests/data/radio_lossless.cfg", "--seed", "3"},
        logs + "ssl_sim_radio.log");
    std::vector<std::string> argv{UBERSIM_SSL_BRIDGE_EXE};
    for (const std::string& option : ports_.bridge_options()) argv.push_back(option);
    bridge_ = std::make_unique<ChildProcess>(argv, logs + "ssl_sim_bridge.log");
    ASSERT_TRUE(radio_->wait_for_output("sim time from", 10)) << radio_->log();
    ASSERT_TRUE(vision_->wait_for_output("subscribing", 10)) << vision_->log();
    ASSERT_TRUE(bridge_->wait_for_output("vision to", 10)) << bridge_->log();
    physics_ = std::make_unique<ChildProcess>(
        std::vector<std::string>{UBERSIM_PHYSICS_EXE, "--scenario", "division_b_6v6"},
        logs + "ssl_sim_physics.log");
  }

  void TearDown() override {
    if (bridge_) {
      EXPECT_EQ(bridge_->stop(10), 0) << bridge_->log();
    }
  }

  // Sends the command until the robot answers with at least one response.
  std::vector<RobotControlResponse> drive(const RobotControl& control, double seconds) {
    std::vector<RobotControlResponse> responses;
    const auto end = Clock::now() + std::chrono::duration<double>(seconds);
    while (Clock::now() < end) {
      if (auto response = ssl_test::control(blue_, control, 1)) responses.push_back(*response);
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return responses;
  }

  const ssl_test::TestPorts ports_ = ssl_test::TestPorts::from_environment();
  ssl_test::VisionReceiver vision_rx_{"224.5.23.2", ports_.vision};
  ssl_test::UdpClient control_{ports_.control};
  ssl_test::UdpClient blue_{ports_.blue};
  std::unique_ptr<ChildProcess> vision_, radio_, bridge_, physics_;
};

}  // namespace

TEST_F(SslBridgeSimulation, TeleportDriveAndFeedbackThroughTheSslProtocols) {
  // Vision comes through as SSL-Vision packets: the kick-off line-up.
  ASSERT_TRUE(vision_rx_.receive_until(
      [](const SSL_WrapperPacket& p) { return find_blue(p, 2) != nullptr; }, 20))
      << physics_->log() << vision_->log() << bridge_->log();
  bool geometry_seen = false;
  ASSERT_TRUE(vision_rx_.receive_until(
      [&](const SSL_WrapperPacket& p) {
        geometry_seen = geometry_seen || p.has_geometry();
        return geometry_seen;
      },
      5));

  // Teleport the ball; physics acknowledges, so no errors.
  SimulatorCommand ball;
  ball.mutable_control()->mutable_teleport_ball()->set_x(1.5f);
  ball.mutable_control()->mutable_teleport_ball()->set_y(-1.0f);
  auto response = ssl_test::command(control_, ball);
  ASSERT_TRUE(response.has_value()) << bridge_->log();
  EXPECT_EQ(response->errors_size(), 0) << describe(*response);
  // Vision noise is 4 mm per axis: 25 mm is more than 6 sigma.
  EXPECT_TRUE(vision_rx_.receive_until(
      [](const SSL_WrapperPacket& p) {
        if (!p.has_detection()) return false;
        for (const auto& b : p.detection().balls()) {
          if (std::hypot(b.x() - 1500.0, b.y() + 1000.0) < 25.0) return true;
        }
        return false;
      },
      5));

  // Teleport blue 2 to a free spot facing +x, then drive it forward at 1 m/s.
  SimulatorCommand place;
  teleport_blue(place, 2, -1.0f, 2.0f);
  response = ssl_test::command(control_, place);
  ASSERT_TRUE(response.has_value());
  EXPECT_EQ(response->errors_size(), 0) << describe(*response);
  double start_x = 0, start_y = 0;
  ASSERT_TRUE(vision_rx_.receive_until(
      [&](const SSL_WrapperPacket& p) {
        const SSL_DetectionRobot* r = find_blue(p, 2);
        if (r == nullptr || std::hypot(r->x() + 1000.0, r->y() - 2000.0) > 30.0) return false;
        start_x = r->x();
        start_y = r->y();
        return true;
      },
      5));
  RobotControl forward;
  RobotCommand* command = forward.add_robot_commands();
  command->set_id(2);
  MoveLocalVelocity* v = command->mutable_move_command()->mutable_local_velocity();
  v->set_forward(1.0f);
  v->set_left(0);
  v->set_angular(0);
  const auto responses = drive(forward, 1.5);
  ASSERT_FALSE(responses.empty());
  bool feedback_for_robot = false;
  for (const auto& r : responses) {
    EXPECT_EQ(r.errors_size(), 0);
    for (const auto& f : r.feedback()) feedback_for_robot = feedback_for_robot || f.id() == 2;
  }
  EXPECT_TRUE(feedback_for_robot);
  // Real time on a loaded machine: at least 0.3 m of the ~1.3 m it can cover.
  EXPECT_TRUE(vision_rx_.receive_until(
      [&](const SSL_WrapperPacket& p) {
        const SSL_DetectionRobot* r = find_blue(p, 2);
        return r != nullptr && r->x() - start_x > 300.0 && std::abs(r->y() - start_y) < 150.0;
      },
      3))
      << "robot did not move forward";

  // Ball on the dribbler: the feedback reports ball contact.
  SimulatorCommand dribble;
  teleport_blue(dribble, 2, 0.0f, -2.0f);
  dribble.mutable_control()->mutable_teleport_ball()->set_x(0.075f + 0.0215f + 0.001f);
  dribble.mutable_control()->mutable_teleport_ball()->set_y(-2.0f);
  response = ssl_test::command(control_, dribble);
  ASSERT_TRUE(response.has_value());
  EXPECT_EQ(response->errors_size(), 0) << describe(*response);
  RobotControl hold;
  RobotCommand* h = hold.add_robot_commands();
  h->set_id(2);
  h->set_dribbler_speed(3000.0f);  // rpm
  bool contact = false;
  const auto end = Clock::now() + std::chrono::seconds(5);
  while (!contact && Clock::now() < end) {
    if (auto r = ssl_test::control(blue_, hold, 1)) {
      for (const auto& f : r->feedback())
        contact = contact || (f.id() == 2 && f.dribbler_ball_contact());
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  EXPECT_TRUE(contact) << bridge_->log() << radio_->log();
}

namespace {

// The blue robot's x (mm) in the newest frame: reads what waits for 150 ms.
std::optional<double> newest_x(ssl_test::VisionReceiver& vision, uint32_t id) {
  std::optional<double> x;
  const auto end = Clock::now() + std::chrono::milliseconds(150);
  while (Clock::now() < end) {
    const auto packet = vision.receive(0.05);
    if (!packet) continue;
    if (const SSL_DetectionRobot* r = find_blue(*packet, id)) x = r->x();
  }
  return x;
}

}  // namespace

// grSim's own protocol end to end: a replacement places the robot, commands on
// the grSim port drive it through the radio emulator, and a team that falls
// silent keeps its last command for the hold (1 s), then its robot stops; the
// robot status from the real radio feedback reaches the sender's status port.
TEST_F(SslBridgeSimulation, GrsimPacketsPlaceAndDriveARobotThatStopsAfterTheTeamFallsSilent) {
  ssl_test::UdpClient grsim(ports_.grsim);
  ASSERT_TRUE(vision_rx_.receive_until(
      [](const SSL_WrapperPacket& p) { return find_blue(p, 2) != nullptr; }, 20))
      << physics_->log() << vision_->log() << bridge_->log();
  grSim_Packet place;
  grSim_RobotReplacement* robot = place.mutable_replacement()->add_robots();
  robot->set_x(-1.5);
  robot->set_y(2.0);
  robot->set_dir(0);
  robot->set_id(2);
  robot->set_yellowteam(false);
  double x0 = 0;
  ASSERT_TRUE(vision_rx_.receive_until(
      [&](const SSL_WrapperPacket& p) {
        grsim.send(place.SerializeAsString());
        const SSL_DetectionRobot* r = find_blue(p, 2);
        if (r == nullptr || std::hypot(r->x() + 1500.0, r->y() - 2000.0) > 30.0) return false;
        x0 = r->x();
        return true;
      },
      5))
      << bridge_->log();

  // Driven at 1 m/s for 0.8 s, one packet every 10 ms.
  const auto drive_end = Clock::now() + std::chrono::milliseconds(800);
  while (Clock::now() < drive_end) {
    grsim.send(ubersim::test::grsim_forward_command(false, 2, 1.0f));
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  // Then one packet at 0.5 m/s and silence: it keeps going for the hold.
  grsim.send(ubersim::test::grsim_forward_command(false, 2, 0.5f));
  const auto silent_from = Clock::now();
  const std::optional<double> x_silent = newest_x(vision_rx_, 2);
  ASSERT_TRUE(x_silent.has_value());
  EXPECT_GT(*x_silent - x0, 200.0) << "the robot did not move on grSim commands";
  std::this_thread::sleep_for(std::chrono::milliseconds(650) - (Clock::now() - silent_from));
  const std::optional<double> x_held = newest_x(vision_rx_, 2);
  ASSERT_TRUE(x_held.has_value());
  // Beyond the radio's 0.25 s command timeout, still driving at ~0.5 m/s.
  EXPECT_GT(*x_held - *x_silent, 150.0) << "the robot stopped before the hold";
  // Well after the hold (1 s) it stands.
  std::this_thread::sleep_for(std::chrono::milliseconds(1800) - (Clock::now() - silent_from));
  const std::optional<double> x_a = newest_x(vision_rx_, 2);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const std::optional<double> x_b = newest_x(vision_rx_, 2);
  ASSERT_TRUE(x_a.has_value() && x_b.has_value());
  EXPECT_LT(std::abs(*x_b - *x_a), 20.0) << "the robot still moves after the hold";

  // The ball put at its kicker, the spinner on: grSim's robot status from the
  // real radio feedback reaches the sender's blue status port.
  ssl_test::UdpEndpoint team;
  ssl_test::UdpEndpoint status(ports_.grsim_blue_status);
  grSim_Packet at_kicker;
  grSim_RobotReplacement* again = at_kicker.mutable_replacement()->add_robots();
  again->set_x(0);
  again->set_y(-2.0);
  again->set_dir(0);
  again->set_id(2);
  again->set_yellowteam(false);
  at_kicker.mutable_replacement()->mutable_ball()->set_x(0.075 + 0.0215 + 0.001);
  at_kicker.mutable_replacement()->mutable_ball()->set_y(-2.0);
  at_kicker.mutable_replacement()->mutable_ball()->set_vx(0);
  at_kicker.mutable_replacement()->mutable_ball()->set_vy(0);
  team.send(ports_.grsim, at_kicker.SerializeAsString());
  grSim_Packet spin;
  spin.ParseFromString(ubersim::test::grsim_forward_command(false, 2, 0.0f));
  spin.mutable_commands()->mutable_robot_commands(0)->set_spinner(true);
  bool infrared = false;
  const auto end = Clock::now() + std::chrono::seconds(5);
  while (!infrared && Clock::now() < end) {
    team.send(ports_.grsim, spin.SerializeAsString());
    if (const auto bytes = status.receive(0.02)) {
      Robots_Status robots;
      ASSERT_TRUE(robots.ParseFromString(*bytes));
      for (const Robot_Status& r : robots.robots_status()) {
        infrared = infrared || (r.robot_id() == 2 && r.infrared());
      }
    }
  }
  EXPECT_TRUE(infrared) << bridge_->log() << radio_->log();
  EXPECT_EQ(bridge_->stop(10), 0);
  EXPECT_NE(bridge_->log().find("grSim stops (team silent 1 s) blue=1"), std::string::npos)
      << bridge_->log();
  bridge_.reset();
}
