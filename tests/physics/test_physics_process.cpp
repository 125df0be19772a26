// The real ubersim_physics process over real LCM (run in its own network
// namespace by run_isolated.sh): control requests and their acknowledgements,
// lockstep stepping, commands, pause/resume, reset, geometry, and a clean exit
// on SIGINT.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <functional>
#include <string>
#include <thread>
#include <ubersim/field_geometry_t.hpp>
#include <ubersim/sim_commands_t.hpp>
#include <ubersim/sim_control_ack_t.hpp>
#include <ubersim/sim_control_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <vector>

#include "child_process.hpp"
#include "ubersim/common_options.hpp"
#include "ubersim/message_bus.hpp"
#include "ubersim/topics.hpp"

namespace {

using namespace std::chrono_literals;
using ubersim::test::ChildProcess;

const std::string kPhysics = UBERSIM_PHYSICS_EXE;

class PhysicsProcess : public ::testing::Test {
 protected:
  PhysicsProcess() : bus_(ubersim::with_receive_buffer(ubersim::default_lcm_url())) {
    ubersim::subscribe(
        bus_, channels_, ubersim::topics::kSimState,
        [this](const ubersim::sim_state_t& s) { states_.push_back(s); }, 100000);
    ubersim::subscribe(bus_, channels_, ubersim::topics::kSimControlAck,
                       [this](const ubersim::sim_control_ack_t& a) { acks_.push_back(a); });
    ubersim::subscribe(bus_, channels_, ubersim::topics::kSimGeometry,
                       [this](const ubersim::field_geometry_t& g) { geometries_.push_back(g); });
  }

  // Handles messages until `done` or the timeout; returns done().
  bool pump_until(const std::function<bool()>& done, std::chrono::milliseconds timeout = 5000ms) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (!done()) {
      if (std::chrono::steady_clock::now() > deadline) return false;
      bus_.wait_and_handle(20);
    }
    return true;
  }

  ubersim::sim_control_t request(int8_t action) {
    ubersim::sim_control_t r{};
    r.request_id = ++last_id_;
    r.sender = "test_physics_process";
    r.action = action;
    return r;
  }

  // Sends a request and waits for its acknowledgement.
  ubersim::sim_control_ack_t call(const ubersim::sim_control_t& r) {
    ubersim::publish(bus_, channels_, ubersim::topics::kSimControl, r);
    const bool got = pump_until([&] { return find_ack(r.request_id) != nullptr; });
    EXPECT_TRUE(got) << "no acknowledgement for request " << r.request_id;
    return got ? *find_ack(r.request_id) : ubersim::sim_control_ack_t{};
  }

  const ubersim::sim_control_ack_t* find_ack(int64_t id) const {
    for (const auto& a : acks_) {
      if (a.request_id == id) return &a;
    }
    return nullptr;
  }

  // Pings until the server answers (it may still be starting up).
  bool wait_for_server() {
    for (int i = 0; i < 100; ++i) {
      auto r = request(ubersim::sim_control_t::PING);
      ubersim::publish(bus_, channels_, ubersim::topics::kSimControl, r);
      if (pump_until([&] { return find_ack(r.request_id) != nullptr; }, 100ms)) return true;
    }
    return false;
  }

  const ubersim::robot_state_t* robot(const ubersim::sim_state_t& s, int team, int id) {
    for (const auto& r : s.robots) {
      if (r.team == team && r.robot_id == id) return &r;
    }
    return nullptr;
  }

  ubersim::ChannelNames channels_;
  ubersim::MessageBus bus_;
  std::vector<ubersim::sim_state_t> states_;
  std::vector<ubersim::sim_control_ack_t> acks_;
  std::vector<ubersim::field_geometry_t> geometries_;
  int64_t last_id_ = 1000;
};

TEST_F(PhysicsProcess, AnswersControlStepsInLockstepAndExitsCleanly) {
  ChildProcess physics({kPhysics, "--lockstep", "--scenario", "division_b_6v6", "-q"}, "");
  ASSERT_TRUE(physics.running());
  ASSERT_TRUE(wait_for_server());
  ASSERT_TRUE(pump_until([&] { return !geometries_.empty(); }));
  EXPECT_EQ(geometries_.back().name, "division_b");
  EXPECT_DOUBLE_EQ(geometries_.back().field_length, 9.0);

  // PING: same id and sender back.
  auto ping = request(ubersim::sim_control_t::PING);
  auto ack = call(ping);
  EXPECT_TRUE(ack.ok);
  EXPECT_EQ(ack.sender, "test_physics_process");
  EXPECT_EQ(ack.step, 0);

  // PLACE the ball, rolling.
  auto place = request(ubersim::sim_control_t::PLACE);
  place.has_ball = true;
  place.ball.position[0] = 1.0;
  place.ball.position[1] = 0.5;
  place.ball.linear_velocity[0] = 1.0;
  ack = call(place);
  EXPECT_TRUE(ack.ok) << ack.message;
  ASSERT_FALSE(states_.empty());
  EXPECT_NEAR(states_.back().ball.position[0], 1.0, 1e-9);

  // STEP 24: 24 states, one per step, then the acknowledgement.
  states_.clear();
  auto step = request(ubersim::sim_control_t::STEP);
  step.step_count = 24;
  ack = call(step);
  EXPECT_TRUE(ack.ok) << ack.message;
  EXPECT_EQ(ack.step, 24);
  ASSERT_EQ(states_.size(), 24u);
  for (std::size_t i = 0; i < states_.size(); ++i) {
    EXPECT_EQ(states_[i].step, static_cast<int64_t>(i + 1));
    EXPECT_NEAR(states_[i].sim_time, (i + 1) * states_[i].dt, 1e-12);
    EXPECT_LT(states_[i].speed_factor, 0);  // lockstep
  }
  EXPECT_NEAR(states_.back().dt, 1.0 / 240, 1e-12);
  EXPECT_GT(states_.back().ball.position[0], 1.05);
  EXPECT_EQ(states_.back().num_robots, 12);

  // Nothing moves without STEP.
  const int64_t last_step = states_.back().step;
  pump_until([] { return false; }, 300ms);
  EXPECT_EQ(states_.back().step, last_step);

  // SIM_COMMANDS: yellow 0 forward, plus a command for a robot that does not exist.
  ubersim::sim_commands_t packet{};
  packet.team = 0;
  packet.sequence = 1;
  packet.t_received = states_.back().sim_time;
  packet.t_apply = states_.back().sim_time + 0.02;
  packet.command_timeout = 0;
  ubersim::robot_command_t forward{};
  forward.robot_id = 0;
  forward.mode = ubersim::robot_command_t::MODE_LOCAL_VELOCITY;
  forward.vx = 1.0;
  ubersim::robot_command_t ghost = forward;
  ghost.robot_id = 42;
  packet.commands = {forward, ghost};
  packet.num_commands = 2;
  const double x0 = robot(states_.back(), 0, 0)->x;
  ubersim::publish(bus_, channels_, ubersim::topics::kSimCommands, packet);
  // A ping after it: LCM keeps order on one socket, so the packet is in when
  // the ping is answered.
  call(request(ubersim::sim_control_t::PING));
  step.request_id = ++last_id_;
  step.step_count = 240;
  ack = call(step);
  ASSERT_TRUE(ack.ok);
  const auto* y0 = robot(states_.back(), 0, 0);
  ASSERT_NE(y0, nullptr);
  EXPECT_GT(y0->x - x0, 0.5);  // about 0.8 m in 1 s with the ramp
  EXPECT_NEAR(y0->vx, 1.0, 0.1);
  EXPECT_NEAR(y0->last_command_time, packet.t_apply, 1.5 / 240);
  EXPECT_EQ(y0->num_wheels, 4);
  EXPECT_EQ(y0->robot_type, "omni4_ssl");

  // As fast as possible, then PAUSE: the step count stops.
  auto speed = request(ubersim::sim_control_t::SET_SPEED);
  speed.speed_factor = 0;
  EXPECT_TRUE(call(speed).ok);
  ASSERT_TRUE(pump_until([&] { return states_.back().step > ack.step + 100; }));
  EXPECT_TRUE(call(request(ubersim::sim_control_t::PAUSE)).ok);
  pump_until([] { return false; }, 100ms);
  const int64_t paused_at = states_.back().step;
  EXPECT_TRUE(states_.back().paused);
  pump_until([] { return false; }, 300ms);
  EXPECT_EQ(states_.back().step, paused_at);
  EXPECT_TRUE(call(request(ubersim::sim_control_t::RESUME)).ok);
  ASSERT_TRUE(pump_until([&] { return states_.back().step > paused_at + 100; }));
  EXPECT_FALSE(states_.back().paused);
  EXPECT_EQ(states_.back().speed_factor, 0.0);
  speed = request(ubersim::sim_control_t::SET_SPEED);
  speed.speed_factor = -1;
  EXPECT_TRUE(call(speed).ok);

  // RESET: back to the scenario at step 0.
  states_.clear();
  ack = call(request(ubersim::sim_control_t::RESET));
  EXPECT_TRUE(ack.ok);
  EXPECT_EQ(ack.step, 0);
  ASSERT_FALSE(states_.empty());
  EXPECT_EQ(states_.back().step, 0);
  EXPECT_EQ(states_.back().sim_time, 0.0);
  EXPECT_NEAR(robot(states_.back(), 0, 0)->x, -4.2, 1e-6);
  EXPECT_NEAR(states_.back().ball.position[0], 0.0, 1e-9);

  // Geometry on request; refused requests say why.
  geometries_.clear();
  EXPECT_TRUE(call(request(ubersim::sim_control_t::REQUEST_GEOMETRY)).ok);
  EXPECT_TRUE(pump_until([&] { return !geometries_.empty(); }));
  auto bad_step = request(ubersim::sim_control_t::STEP);
  bad_step.step_count = 0;
  ack = call(bad_step);
  EXPECT_FALSE(ack.ok);
  EXPECT_NE(ack.message.find("step_count"), std::string::npos);
  auto unknown = request(99);
  EXPECT_FALSE(call(unknown).ok);
  auto bad_place = request(ubersim::sim_control_t::PLACE);
  ubersim::robot_placement_t newcomer{};
  newcomer.team = 1;
  newcomer.robot_id = 11;
  newcomer.present = true;  // no robot_type for a new robot
  bad_place.robots = {newcomer};
  bad_place.num_robots = 1;
  EXPECT_FALSE(call(bad_place).ok);

  EXPECT_EQ(physics.stop(5, SIGINT), 0);
}

TEST_F(PhysicsProcess, PacesToTheWallClockAndStopsAfterItsDuration) {
  // 4 x real time for 2 s of sim time: about half a second of wall time.
  const auto start = std::chrono::steady_clock::now();
  ChildProcess physics(
      {kPhysics, "--speed", "4", "--duration", "2", "--scenario", "field2002_5v5", "-q"}, "");
  ASSERT_TRUE(physics.running());
  const int code = physics.wait(20);
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(code, 0);
  // Never faster than asked (it may be slower on a loaded machine).
  EXPECT_GT(wall, 2.0 / 4 - 0.05);
  bus_.handle_pending();
  if (!states_.empty()) {
    EXPECT_NEAR(states_.back().sim_time, 2.0, 1e-9);
    EXPECT_EQ(states_.back().speed_factor, 4.0);
  }
}

}  // namespace
