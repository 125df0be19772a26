// The same driving scenario, once through the SSL protocol bridge and once
// through LCM directly (radio_packet_t on RADIO_BLUE), with physics in
// lockstep and a lossless radio: the robot's trajectories must be identical.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <map>
#include <set>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/robot_command_t.hpp>
#include <ubersim/sim_commands_t.hpp>
#include <ubersim/sim_control_ack_t.hpp>
#include <ubersim/sim_control_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <ubersim/team_t.hpp>

#include "child_process.hpp"
#include "ssl_client.hpp"
#include "ubersim/common_options.hpp"
#include "ubersim/message_bus.hpp"

namespace {

using ubersim::test::ChildProcess;
using Clock = std::chrono::steady_clock;

constexpr int kRobot = 2;
constexpr int kCommands = 12;
constexpr int kStepsPerCommand = 10;  // 240 Hz physics: a command every 1/24 s

struct Pose {
  double x, y, orientation;
};

// Command number i of the scenario: a curve with varying speed.
void scenario_command(int i, double& forward, double& left, double& angular) {
  forward = 0.4 + 0.05 * i;
  left = (i % 3 == 0) ? 0.25 : -0.125;
  angular = 0.5 * std::sin(0.5 * i);
}

// Pose of the robot after each physics step (a paused or lockstep physics
// also republishes its state now and then: keyed by step, repeats collapse).
using Trajectory = std::map<int64_t, Pose>;

Trajectory run_scenario(bool through_bridge, const std::string& name) {
  const std::string logs = ::testing::TempDir();
  const ssl_test::TestPorts ports = ssl_test::TestPorts::from_environment();
  ChildProcess radio(
      {UBERSIM_RADIO_EXE, "--profile",
       std::string(UBERSIM_SOURCE_DIR) + "/tests/data/radio_lossless.cfg", "--seed", "5"},
      logs + name + "_radio.log");
  std::unique_ptr<ChildProcess> bridge;
  if (through_bridge) {
    std::vector<std::string> argv{UBERSIM_SSL_BRIDGE_EXE};
    for (const std::string& option : ports.bridge_options()) argv.push_back(option);
    bridge = std::make_unique<ChildProcess>(argv, logs + name + "_bridge.log");
    if (!bridge->wait_for_output("vision to", 10)) throw std::runtime_error(bridge->log());
  }
  if (!radio.wait_for_output("sim time from", 10)) throw std::runtime_error(radio.log());
  ChildProcess physics(
      {UBERSIM_PHYSICS_EXE, "--lockstep", "--seed", "5", "--scenario", "division_b_6v6"},
      logs + name + "_physics.log");

  ubersim::MessageBus bus(ubersim::with_receive_buffer(ubersim::default_lcm_url()));
  Trajectory poses;
  std::set<int64_t> forwarded;
  int64_t awaited = -1;
  bool acked = false;
  double sim_time = 0;
  bus.subscribe<ubersim::sim_state_t>("SIM_STATE", [&](const ubersim::sim_state_t& s) {
    sim_time = s.sim_time;
    for (const auto& r : s.robots) {
      if (r.team == ubersim::team_t::BLUE && r.robot_id == kRobot) {
        poses[s.step] = Pose{r.x, r.y, r.orientation};
      }
    }
  });
  bus.subscribe<ubersim::sim_commands_t>(
      "SIM_COMMANDS", [&](const ubersim::sim_commands_t& c) { forwarded.insert(c.sequence); });
  bus.subscribe<ubersim::sim_control_ack_t>("SIM_CONTROL_ACK",
                                            [&](const ubersim::sim_control_ack_t& a) {
                                              if (a.request_id == awaited) acked = true;
                                            });
  auto wait = [&](const std::function<bool()>& done, double timeout_s) {
    const auto deadline = Clock::now() + std::chrono::duration<double>(timeout_s);
    while (!done() && Clock::now() < deadline) bus.wait_and_handle(10);
    return done();
  };
  int64_t request_id = 1000;
  auto control = [&](int8_t action, int32_t steps, double timeout_s = 30) {
    ubersim::sim_control_t request{};
    request.request_id = awaited = ++request_id;
    request.sender = "ssl_equivalence";
    request.action = action;
    request.step_count = steps;
    acked = false;
    bus.publish("SIM_CONTROL", request);
    return wait([&] { return acked; }, timeout_s);
  };
  bool ready = false;
  for (int i = 0; i < 50 && !ready; ++i) ready = control(ubersim::sim_control_t::PING, 0, 0.2);
  if (!ready) throw std::runtime_error("physics did not answer: " + physics.log());
  if (!control(ubersim::sim_control_t::STEP, 1)) throw std::runtime_error("no step");

  ssl_test::UdpClient blue(ports.blue);
  poses.clear();
  for (int i = 0; i < kCommands; ++i) {
    double forward, left, angular;
    scenario_command(i, forward, left, angular);
    if (through_bridge) {
      RobotControl control_message;
      RobotCommand* c = control_message.add_robot_commands();
      c->set_id(kRobot);
      MoveLocalVelocity* v = c->mutable_move_command()->mutable_local_velocity();
      v->set_forward(static_cast<float>(forward));
      v->set_left(static_cast<float>(left));
      v->set_angular(static_cast<float>(angular));
      if (!ssl_test::control(blue, control_message)) throw std::runtime_error("no response");
    } else {
      ubersim::radio_packet_t packet{};
      packet.team = ubersim::team_t::BLUE;
      packet.sequence = i + 1;  // what the bridge numbers its packets
      packet.t_sent = sim_time;
      ubersim::robot_command_t c{};
      c.robot_id = kRobot;
      c.mode = ubersim::robot_command_t::MODE_LOCAL_VELOCITY;
      // The SSL protocol carries float32: send the same values.
      c.vx = static_cast<float>(forward);
      c.vy = static_cast<float>(left);
      c.omega = static_cast<float>(angular);
      packet.commands.push_back(c);
      packet.num_commands = 1;
      bus.publish("RADIO_BLUE", packet);
    }
    if (!wait([&] { return forwarded.count(i + 1) != 0; }, 5)) {
      throw std::runtime_error("radio did not forward command " + std::to_string(i));
    }
    if (!control(ubersim::sim_control_t::STEP, kStepsPerCommand)) {
      throw std::runtime_error("no step ack");
    }
  }
  if (!control(ubersim::sim_control_t::STEP, 24)) throw std::runtime_error("no step ack");
  wait([] { return false; }, 0.1);
  return poses;
}

}  // namespace

TEST(SslBridgeEquivalence, BridgeAndLcmGiveTheSameTrajectory) {
  const Trajectory lcm = run_scenario(false, "ssl_equiv_lcm");
  const Trajectory bridge = run_scenario(true, "ssl_equiv_bridge");
  ASSERT_GE(lcm.size(), static_cast<size_t>(kCommands * kStepsPerCommand + 24));
  ASSERT_EQ(bridge.size(), lcm.size());
  for (const auto& [step, pose] : lcm) {
    const auto other = bridge.find(step);
    ASSERT_NE(other, bridge.end()) << "step " << step;
    EXPECT_EQ(other->second.x, pose.x) << "step " << step;
    EXPECT_EQ(other->second.y, pose.y) << "step " << step;
    EXPECT_EQ(other->second.orientation, pose.orientation) << "step " << step;
  }
  // And the robot did drive: the comparison is not between two standing robots.
  const Pose& first = lcm.begin()->second;
  const Pose& last = lcm.rbegin()->second;
  const double moved = std::hypot(last.x - first.x, last.y - first.y);
  EXPECT_GT(moved, 0.1);
}
