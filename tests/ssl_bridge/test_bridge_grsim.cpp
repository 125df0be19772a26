// grSim's own protocol against the real ubersim_ssl_bridge process: a client
// that encodes grSim_Packet with grSim's .proto definitions (our copies,
// checked field for field by test_ssl_protocol_definitions) sends it over real
// UDP; the test reads RADIO_<TEAM> and SIM_CONTROL over real LCM, feeds
// RADIO_FEEDBACK_<TEAM> and receives Robots_Status on the status ports.
// ISOLATED: its own network namespace, ports from the LCM port.
#include <arpa/inet.h>
#include <grSim_Packet.pb.h>
#include <grSim_Robotstatus.pb.h>
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <sstream>
#include <thread>
#include <ubersim/radio_feedback_t.hpp>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/sim_control_t.hpp>
#include <ubersim/sim_state_t.hpp>

#include "child_process.hpp"
#include "ssl_client.hpp"
#include "ubersim/common_options.hpp"
#include "ubersim/message_bus.hpp"

namespace {

using Clock = std::chrono::steady_clock;
using ubersim::test::ChildProcess;

constexpr double kPi = 3.14159265358979323846;
constexpr double kSpinnerSpeed = 1000;  // rad/s: omni4_ssl's DRIBBLER_MAX_SPEED

// VmRSS of a process in kB (/proc/<pid>/status), -1 when gone.
long vm_rss_kb(pid_t pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
  }
  return -1;
}

using ssl_test::UdpEndpoint;

grSim_Robot_Command* add_robot(grSim_Packet& packet, bool yellow, uint32_t id) {
  grSim_Commands* commands = packet.mutable_commands();
  commands->set_timestamp(12.5);
  commands->set_isteamyellow(yellow);
  grSim_Robot_Command* robot = commands->add_robot_commands();
  robot->set_id(id);
  robot->set_kickspeedx(0);
  robot->set_kickspeedz(0);
  robot->set_veltangent(0);
  robot->set_velnormal(0);
  robot->set_velangular(0);
  robot->set_spinner(false);
  robot->set_wheelsspeed(false);
  return robot;
}

const ubersim::robot_command_t* find(const ubersim::radio_packet_t& packet, int id) {
  for (const auto& command : packet.commands) {
    if (command.robot_id == id) return &command;
  }
  return nullptr;
}

class GrsimBridge : public ::testing::Test {
 protected:
  void SetUp() override {
    std::vector<std::string> argv{UBERSIM_SSL_BRIDGE_EXE};
    for (const std::string& option : ports_.bridge_options()) argv.push_back(option);
    bridge_ = std::make_unique<ChildProcess>(argv, ::testing::TempDir() + "ssl_bridge_grsim.log");
    ASSERT_TRUE(bridge_->wait_for_output("grSim protocol", 10)) << bridge_->log();
    for (const char* channel : {"RADIO_BLUE", "RADIO_YELLOW"}) {
      bus_.subscribe<ubersim::radio_packet_t>(
          channel,
          [this, channel](const ubersim::radio_packet_t& p) { radio_[channel].push_back(p); });
    }
    bus_.subscribe<ubersim::sim_control_t>(
        "SIM_CONTROL", [this](const ubersim::sim_control_t& c) { control_.push_back(c); });
  }
  void TearDown() override {
    if (bridge_) {
      EXPECT_EQ(bridge_->stop(10), 0) << bridge_->log();
    }
  }

  // Sends `packet` until a message on the bus satisfies `seen` (the bridge may still subscribe).
  bool send_until(const grSim_Packet& packet, const std::function<bool()>& seen) {
    const std::string bytes = packet.SerializeAsString();
    for (int attempt = 0; attempt < 40; ++attempt) {
      client_.send(ports_.grsim, bytes);
      const auto deadline = Clock::now() + std::chrono::milliseconds(100);
      while (Clock::now() < deadline) {
        bus_.wait_and_handle(10);
        if (seen()) return true;
      }
    }
    return false;
  }
  // The newest packet on the channel with robot `id`, once one arrived.
  const ubersim::robot_command_t* newest(const std::string& channel, int id) {
    const auto& packets = radio_[channel];
    return packets.empty() ? nullptr : find(packets.back(), id);
  }

  const ssl_test::TestPorts ports_ = ssl_test::TestPorts::from_environment();
  ubersim::MessageBus bus_{ubersim::with_receive_buffer(ubersim::default_lcm_url())};
  std::unique_ptr<ChildProcess> bridge_;
  UdpEndpoint client_;
  std::map<std::string, std::vector<ubersim::radio_packet_t>> radio_;
  std::vector<ubersim::sim_control_t> control_;
};

}  // namespace

TEST_F(GrsimBridge, VelocitiesKickAndSpinnerReachTheTeamsRadio) {
  grSim_Packet packet;
  grSim_Robot_Command* robot = add_robot(packet, false, 3);
  robot->set_veltangent(1.5f);
  robot->set_velnormal(-0.5f);
  robot->set_velangular(2.0f);
  robot->set_kickspeedx(4.0f);
  robot->set_spinner(true);
  ASSERT_TRUE(send_until(packet, [&] { return newest("RADIO_BLUE", 3) != nullptr; }))
      << bridge_->log();
  const ubersim::robot_command_t& c = *newest("RADIO_BLUE", 3);
  EXPECT_EQ(c.mode, int8_t{ubersim::robot_command_t::MODE_LOCAL_VELOCITY});
  EXPECT_DOUBLE_EQ(c.vx, 1.5);
  EXPECT_DOUBLE_EQ(c.vy, -0.5);
  EXPECT_DOUBLE_EQ(c.omega, 2.0);
  EXPECT_DOUBLE_EQ(c.kick_speed, 4.0);  // kickspeedz 0: a flat kick
  EXPECT_DOUBLE_EQ(c.chip_speed, 0.0);
  EXPECT_DOUBLE_EQ(c.dribbler_speed, kSpinnerSpeed);
  EXPECT_EQ(radio_["RADIO_BLUE"].back().team, 1);  // team_t.BLUE
  EXPECT_TRUE(radio_["RADIO_YELLOW"].empty());

  // kickspeedx with kickspeedz: a chip leaving at (3, 4) m/s, for the yellow team.
  grSim_Packet chip;
  grSim_Robot_Command* yellow = add_robot(chip, true, 5);
  yellow->set_kickspeedx(3.0f);
  yellow->set_kickspeedz(4.0f);
  ASSERT_TRUE(send_until(chip, [&] { return newest("RADIO_YELLOW", 5) != nullptr; }));
  const ubersim::robot_command_t& y = *newest("RADIO_YELLOW", 5);
  EXPECT_DOUBLE_EQ(y.kick_speed, 0.0);
  EXPECT_NEAR(y.chip_speed, 5.0, 1e-6);
  EXPECT_NEAR(y.chip_angle, std::atan2(4.0, 3.0), 1e-6);
  EXPECT_DOUBLE_EQ(y.dribbler_speed, 0.0);
}

TEST_F(GrsimBridge, WheelSpeedsFollowGrsimsWheelNumbering) {
  // grSim's wheels 1..4 sit at 60, 135, 225, 300 degrees; omni4_ssl's at 57,
  // 135, 225, 303: the same order. Values are wheel speeds in rad/s.
  grSim_Packet packet;
  grSim_Robot_Command* robot = add_robot(packet, false, 1);
  robot->set_wheelsspeed(true);
  robot->set_wheel1(10);
  robot->set_wheel2(-20);
  robot->set_wheel3(30);
  robot->set_wheel4(-40);
  ASSERT_TRUE(send_until(packet, [&] { return newest("RADIO_BLUE", 1) != nullptr; }));
  const ubersim::robot_command_t& c = *newest("RADIO_BLUE", 1);
  EXPECT_EQ(c.mode, int8_t{ubersim::robot_command_t::MODE_WHEEL_SPEEDS});
  EXPECT_EQ(c.wheel_speeds, (std::vector<double>{10, -20, 30, -40}));

  // A wheel grSim is not given keeps its speed.
  grSim_Packet partial;
  grSim_Robot_Command* again = add_robot(partial, false, 1);
  again->set_wheelsspeed(true);
  again->set_wheel2(5);
  ASSERT_TRUE(send_until(partial, [&] {
    const auto* n = newest("RADIO_BLUE", 1);
    return n != nullptr && n->wheel_speeds.size() == 4 && n->wheel_speeds[1] == 5;
  }));
  EXPECT_EQ(newest("RADIO_BLUE", 1)->wheel_speeds, (std::vector<double>{10, 5, 30, -40}));
}

TEST_F(GrsimBridge, ReplacementsBecomeSimControlPlacements) {
  grSim_Packet packet;
  grSim_Replacement* replacement = packet.mutable_replacement();
  grSim_RobotReplacement* add = replacement->add_robots();
  add->set_x(1.0);
  add->set_y(-1.0);
  add->set_dir(90);
  add->set_id(2);
  add->set_yellowteam(true);
  grSim_RobotReplacement* off = replacement->add_robots();
  off->set_x(0);
  off->set_y(0);
  off->set_dir(0);
  off->set_id(4);
  off->set_yellowteam(false);
  off->set_turnon(false);
  grSim_BallReplacement* ball = replacement->mutable_ball();
  ball->set_x(0.5);
  ball->set_y(0.25);
  ball->set_vx(-1.0);
  ball->set_vy(2.0);
  ASSERT_TRUE(send_until(packet, [&] { return !control_.empty(); })) << bridge_->log();
  const ubersim::sim_control_t& place = control_.front();
  EXPECT_EQ(place.action, int8_t{ubersim::sim_control_t::PLACE});
  ASSERT_EQ(place.num_robots, 2);
  EXPECT_EQ(place.robots[0].team, 0);  // team_t.YELLOW
  EXPECT_EQ(place.robots[0].robot_id, 2);
  EXPECT_TRUE(place.robots[0].present);
  EXPECT_NEAR(place.robots[0].x, 1.0, 1e-6);
  EXPECT_NEAR(place.robots[0].y, -1.0, 1e-6);
  EXPECT_NEAR(place.robots[0].orientation, kPi / 2, 1e-6);
  EXPECT_EQ(place.robots[1].robot_id, 4);
  EXPECT_FALSE(place.robots[1].present);  // turnon = false takes it off the field
  ASSERT_TRUE(place.has_ball);
  EXPECT_NEAR(place.ball.position[0], 0.5, 1e-6);
  EXPECT_NEAR(place.ball.position[1], 0.25, 1e-6);
  EXPECT_NEAR(place.ball.linear_velocity[0], -1.0, 1e-6);
  EXPECT_NEAR(place.ball.linear_velocity[1], 2.0, 1e-6);
}

TEST_F(GrsimBridge, BallVelocityNotGivenKeepsTheBallsCurrentOne) {
  ubersim::sim_state_t state{};
  state.sim_time = 3.0;
  state.ball_present = true;
  state.ball.position[0] = -2;
  state.ball.linear_velocity[0] = 0.75;
  state.ball.linear_velocity[1] = -0.5;
  grSim_Packet packet;
  packet.mutable_replacement()->mutable_ball()->set_x(1.0);
  packet.mutable_replacement()->mutable_ball()->set_y(2.0);
  ASSERT_TRUE(send_until(packet, [&] {
    bus_.publish("SIM_STATE", state);
    return !control_.empty() && std::abs(control_.back().ball.linear_velocity[0] - 0.75) < 1e-6;
  })) << bridge_->log();
  EXPECT_NEAR(control_.back().ball.linear_velocity[1], -0.5, 1e-6);
  EXPECT_NEAR(control_.back().ball.position[0], 1.0, 1e-6);
}

TEST_F(GrsimBridge, RobotStatusGoesToTheSendersStatusPort) {
  UdpEndpoint blue_status(ports_.grsim_blue_status);
  ubersim::radio_feedback_t feedback{};
  feedback.team = 1;  // BLUE
  feedback.t_measured = 1.0;
  ubersim::robot_feedback_t robot{};
  robot.robot_id = 3;
  robot.ball_contact = true;
  robot.kicker_charged = true;
  feedback.robots = {robot};
  feedback.num_robots = 1;
  grSim_Packet kick;
  add_robot(kick, false, 3)->set_kickspeedx(5.0f);
  const std::string bytes = kick.SerializeAsString();
  std::optional<Robots_Status> infrared;
  for (int attempt = 0; attempt < 50 && !infrared; ++attempt) {
    bus_.publish("RADIO_FEEDBACK_BLUE", feedback);
    client_.send(ports_.grsim, bytes);  // grSim sends status after a datagram
    if (auto received = blue_status.receive(0.1)) {
      infrared.emplace();
      ASSERT_TRUE(infrared->ParseFromString(*received));
    }
  }
  ASSERT_TRUE(infrared.has_value()) << bridge_->log();
  ASSERT_EQ(infrared->robots_status_size(), 1);
  EXPECT_EQ(infrared->robots_status(0).robot_id(), 3);
  EXPECT_TRUE(infrared->robots_status(0).infrared());
  EXPECT_FALSE(infrared->robots_status(0).flat_kick());

  // The kicker discharged while the command asked a flat kick: a flat kick.
  feedback.t_measured = 1.1;
  feedback.robots[0].kicker_charged = false;
  feedback.robots[0].ball_contact = false;
  std::optional<Robots_Status> kicked;
  for (int attempt = 0; attempt < 50 && !kicked; ++attempt) {
    bus_.publish("RADIO_FEEDBACK_BLUE", feedback);
    client_.send(ports_.grsim, bytes);
    if (auto received = blue_status.receive(0.1)) {
      kicked.emplace();
      ASSERT_TRUE(kicked->ParseFromString(*received));
    }
  }
  ASSERT_TRUE(kicked.has_value()) << bridge_->log();
  ASSERT_EQ(kicked->robots_status_size(), 1);
  EXPECT_FALSE(kicked->robots_status(0).infrared());
  EXPECT_TRUE(kicked->robots_status(0).flat_kick());
  EXPECT_FALSE(kicked->robots_status(0).chip_kick());
}

TEST_F(GrsimBridge, MalformedPacketsAreCountedAndDropped) {
  const std::string garbage("\x0a\xff\xff\xff\xff\x0f\x01\x02", 8);  // length beyond the datagram
  for (int i = 0; i < 25; ++i) client_.send(ports_.grsim, garbage);
  grSim_Packet packet;
  add_robot(packet, false, 7)->set_veltangent(0.25f);
  ASSERT_TRUE(send_until(packet, [&] { return newest("RADIO_BLUE", 7) != nullptr; }));
  ASSERT_EQ(bridge_->stop(10), 0);
  const std::string log = bridge_->log();
  bridge_.reset();
  EXPECT_NE(log.find("grSim datagrams dropped (malformed or too large)=25"), std::string::npos)
      << log;
  EXPECT_NE(log.find("dropped a datagram on the grSim port"), std::string::npos) << log;
}

TEST_F(GrsimBridge, FloodOfFiftyThousandPacketsPerSecondKeepsMemoryFlatAndTheNewestCommand) {
  constexpr int kRate = 50'000;  // packets/s, one robot per packet, both teams
  constexpr double kSeconds = 10;
  std::vector<std::string> packets;
  for (int i = 0; i < 200; ++i) {
    grSim_Packet packet;
    add_robot(packet, i % 2 == 1, static_cast<uint32_t>(i % 11))
        ->set_veltangent(0.001f * static_cast<float>(i));
    packets.push_back(packet.SerializeAsString());
  }
  // Warm up (the bridge's buffers reach their size), then the flood.
  ASSERT_TRUE(send_until(grSim_Packet(), [] { return true; }));
  for (int i = 0; i < 2000; ++i) client_.send(ports_.grsim, packets[static_cast<size_t>(i) % 200]);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const long rss_before = vm_rss_kb(bridge_->pid());
  const auto start = Clock::now();
  long sent = 0;
  long rss_middle = -1;
  while (true) {
    const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    if (elapsed >= kSeconds) break;
    const long due = static_cast<long>(elapsed * kRate);
    while (sent < due) client_.send(ports_.grsim, packets[static_cast<size_t>(sent++) % 200]);
    if (rss_middle < 0 && elapsed > kSeconds / 2) rss_middle = vm_rss_kb(bridge_->pid());
    bus_.handle_pending();  // keep our LCM socket from overflowing
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  while (sent < static_cast<long>(kRate * kSeconds)) {
    client_.send(ports_.grsim, packets[static_cast<size_t>(sent++) % 200]);
  }
  const long rss_after = vm_rss_kb(bridge_->pid());
  std::printf(
      "flood: %ld packets in %.0f s; bridge VmRSS %ld kB before, %ld kB half-way, %ld kB after\n",
      sent, kSeconds, rss_before, rss_middle, rss_after);
  EXPECT_EQ(sent, static_cast<long>(kRate * kSeconds));
  EXPECT_LT(rss_after - rss_before, 4 * 1024) << "memory grows with the flood";
  EXPECT_LT(std::abs(rss_after - rss_middle), 2 * 1024) << "memory grows with the flood";

  // After the flood (once the bridge read what the socket held): each robot's
  // newest command, one robot per packet, is the one applied.
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  grSim_Packet last;
  for (uint32_t id = 0; id < 11; ++id) {
    last.Clear();
    add_robot(last, false, id)->set_veltangent(1.0f + 0.01f * static_cast<float>(id));
    client_.send(ports_.grsim, last.SerializeAsString());
  }
  radio_["RADIO_BLUE"].clear();
  ASSERT_TRUE(send_until(last, [&] {
    const auto& packets_seen = radio_["RADIO_BLUE"];
    if (packets_seen.empty()) return false;
    for (int id = 0; id < 11; ++id) {
      const auto* c = find(packets_seen.back(), id);
      if (c == nullptr || std::abs(c->vx - (1.0 + 0.01 * id)) > 1e-6) return false;
    }
    return true;
  })) << bridge_->log();
  ASSERT_EQ(bridge_->stop(10), 0);
  const std::string log = bridge_->log();
  bridge_.reset();
  const auto at = log.find("grSim commands superseded blue=");
  ASSERT_NE(at, std::string::npos) << log;
  std::printf("%s\n", log.substr(log.find("grSim summary")).c_str());
  EXPECT_GT(std::stol(log.substr(at + 31)), 1000) << "a flood supersedes commands";
}
