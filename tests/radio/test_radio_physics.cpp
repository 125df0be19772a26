// End to end with the real physics server: control software -> RADIO_<TEAM>
// -> ubersim_radio -> SIM_COMMANDS -> ubersim_physics -> SIM_STATE. Physics
// runs in lockstep and the test steps it, so sim time only moves when the test
// says so and a loaded machine cannot change the outcome. (run ISOLATED)
#include <gtest/gtest.h>
#include <stdlib.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/sim_commands_t.hpp>
#include <ubersim/sim_control_ack_t.hpp>
#include <ubersim/sim_control_t.hpp>
#include <ubersim/sim_state_t.hpp>

#include "child_process.hpp"  // tests/support
#include "radio_test_util.hpp"
#include "ubersim/common_options.hpp"
#include "ubersim/message_bus.hpp"
#include "ubersim/topics.hpp"

namespace {

constexpr double kStep = 1.0 / 240;  // the default physics step (checked against SIM_STATE.dt)
constexpr double kEps = 1e-9;

// One robot of each team, far from walls, ball and each other, facing +x.
const char* kScenario =
    "FIELD = division_b\n"
    "BALL = ssl_golf_ball\n"
    "BALL_POSITION = 3 2.5   # m, out of the way\n"
    "YELLOW_0 = omni4_ssl -3.0 -1.0 0\n"
    "BLUE_0 = omni4_ssl -3.0 1.0 0\n";

// A radio profile with a latency of exactly `latency_steps` physics steps
// (written with every digit), no jitter, no loss.
std::string exact_profile(int latency_steps, double timeout) {
  std::ostringstream text;
  text.precision(17);
  text << "MAX_PACKET_RATE = 60\nLATENCY = " << latency_steps * kStep
       << "\nLATENCY_JITTER = 0\nPACKET_LOSS = 0\nROBOT_LOSS = 0\nCOMMAND_TIMEOUT = " << timeout
       << "\nFEEDBACK_RATE = 30\nFEEDBACK_LATENCY = 0.02\nFEEDBACK_LATENCY_JITTER = 0\n"
          "FEEDBACK_PACKET_LOSS = 0\nFEEDBACK_ROBOT_LOSS = 0\n"
          "LIMIT_SPEED = 10\nLIMIT_ANGULAR_SPEED = 60\nLIMIT_WHEEL_SPEED = 1000\n"
          "LIMIT_KICK_SPEED = 20\nLIMIT_DRIBBLER_SPEED = 5000\nSEED = 1\n";
  return text.str();
}

struct Sample {
  double t;
  double speed[2];  // robot 0 of yellow, of blue (m/s)
};

class RadioPhysicsTest : public ::testing::Test {
 protected:
  void start(const std::string& yellow_profile, const std::string& blue_profile) {
    std::string pattern = ::testing::TempDir() + "radio_physics_XXXXXX";
    ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
    dir_ = pattern;
    write(dir_ / "scenario.cfg", kScenario);
    write(dir_ / "yellow.cfg", yellow_profile);
    write(dir_ / "blue.cfg", blue_profile);

    bus_ = std::make_unique<ubersim::MessageBus>(
        ubersim::with_receive_buffer(ubersim::default_lcm_url()));
    ubersim::subscribe(*bus_, channels_, ubersim::topics::kSimState,
                       [this](const ubersim::sim_state_t& s) { on_state(s); });
    ubersim::subscribe(
        *bus_, channels_, ubersim::topics::kSimCommands,
        [this](const ubersim::sim_commands_t& m) { forwarded_[m.team].push_back(m); });
    ubersim::subscribe(*bus_, channels_, ubersim::topics::kSimControlAck,
                       [this](const ubersim::sim_control_ack_t& a) { acks_[a.request_id] = a; });

    physics_ = std::make_unique<ubersim::test::ChildProcess>(
        std::vector<std::string>{UBERSIM_PHYSICS_EXE, "--lockstep", "--scenario",
                                 (dir_ / "scenario.cfg").string()},
        (dir_ / "physics.log").string());
    radio_ = std::make_unique<ubersim::test::ChildProcess>(
        std::vector<std::string>{UBERSIM_RADIO_EXE, "--yellow-profile",
                                 (dir_ / "yellow.cfg").string(), "--blue-profile",
                                 (dir_ / "blue.cfg").string()},
        (dir_ / "radio.log").string());

    // Physics answers once it listens; the emulator once it has a sim time.
    bool physics_up = false;
    for (int i = 0; i < 100 && !physics_up; ++i)
      physics_up = control(ubersim::sim_control_t::PING, 0, 300);
    ASSERT_TRUE(physics_up) << physics_->log();
    bool radio_up = false;
    for (int i = 0; i < 100 && !radio_up; ++i) {
      ASSERT_TRUE(step(1));
      radio_up = send_and_wait(1, 0.0, 300);  // blue robot 0: stand still
    }
    ASSERT_TRUE(radio_up) << radio_->log();
    ASSERT_NEAR(dt_, kStep, 1e-12) << "the test assumes the default 240 Hz physics";
  }

  void TearDown() override {
    if (radio_) {
      EXPECT_EQ(radio_->stop(), 0) << radio_->log();
    }
    if (physics_) {
      EXPECT_EQ(physics_->stop(), 0) << physics_->log();
    }
    if (HasFailure() && radio_ && physics_) {
      std::cerr << "--- radio ---\n" << radio_->log() << "--- physics ---\n" << physics_->log();
    }
    if (!dir_.empty()) std::filesystem::remove_all(dir_);
  }

  static void write(const std::filesystem::path& path, const std::string& text) {
    std::ofstream(path) << text;
  }

  void on_state(const ubersim::sim_state_t& s) {
    dt_ = s.dt;
    now_ = s.sim_time;
    Sample sample{s.sim_time, {-1, -1}};
    for (const auto& r : s.robots)
      if (r.robot_id == 0 && (r.team == 0 || r.team == 1))
        sample.speed[r.team] = std::hypot(r.vx, r.vy);
    samples_.push_back(sample);
  }

  // Sends a SIM_CONTROL request and waits for its acknowledgement.
  bool control(std::int8_t action, int step_count, int timeout_ms = 30000) {
    ubersim::sim_control_t request{};
    request.request_id = ++request_id_;
    request.sender = "test_radio_physics";
    request.action = action;
    request.step_count = step_count;
    request.speed_factor = 0;
    ubersim::publish(*bus_, channels_, ubersim::topics::kSimControl, request);
    const std::int64_t id = request_id_;
    return wait([&] { return acks_.count(id) > 0; }, timeout_ms) && acks_[id].ok;
  }
  bool step(int n) { return control(ubersim::sim_control_t::STEP, n); }

  // Publishes a local-velocity command (vx m/s) for robot 0 on the team's radio
  // channel and waits until the emulator has forwarded it to physics.
  bool send_and_wait(int team, double vx, int timeout_ms = 30000) {
    auto p = radio_test::packet(team, ++sequence_[team], {0});
    p.commands[0].vx = vx;
    ubersim::publish(*bus_, channels_, ubersim::topics::kRadio.of(static_cast<ubersim::Team>(team)),
                     p);
    const std::int64_t sequence = sequence_[team];
    return wait(
        [&] { return !forwarded_[team].empty() && forwarded_[team].back().sequence == sequence; },
        timeout_ms);
  }

  template <class Done>
  bool wait(Done done, int timeout_ms) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
    while (!done()) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                            deadline - std::chrono::steady_clock::now())
                            .count();
      if (left <= 0) return false;
      bus_->wait_and_handle(static_cast<int>(left));
    }
    return true;
  }

  // Speed of `team`'s robot 0 in the last state at or before t.
  double speed_at(int team, double t) const {
    double speed = -1;
    for (const auto& s : samples_)
      if (s.t <= t + kEps) speed = s.speed[team];
    return speed;
  }
  // First sample time after `from` at which the speed is below `below`.
  double first_below(int team, double from, double below) const {
    for (const auto& s : samples_)
      if (s.t > from + kEps && s.speed[team] < below) return s.t;
    return -1;
  }

  ubersim::ChannelNames channels_;
  std::filesystem::path dir_;
  std::unique_ptr<ubersim::MessageBus> bus_;
  std::unique_ptr<ubersim::test::ChildProcess> physics_;
  std::unique_ptr<ubersim::test::ChildProcess> radio_;
  std::map<std::int64_t, ubersim::sim_control_ack_t> acks_;
  std::vector<ubersim::sim_commands_t> forwarded_[2];
  std::vector<Sample> samples_;
  std::int64_t request_id_ = 0;
  std::int64_t sequence_[2] = {0, 0};
  double dt_ = 0;
  double now_ = 0;
};

}  // namespace

// Issue: a velocity command on RADIO_<TEAM> moves the robot, and the delay until
// the ground truth shows the motion starting is the radio latency plus at most
// one physics step.
TEST_F(RadioPhysicsTest, CommandMovesTheRobotAfterTheRadioLatencyPlusAtMostOneStep) {
  const int latency_steps = 8;  // 33.3 ms, the paper's radio latency
  const double latency = latency_steps * kStep;
  start(exact_profile(latency_steps, 1.0), exact_profile(latency_steps, 1.0));
  ASSERT_TRUE(step(120));  // let the robots settle on the ground
  // A robot at rest still creeps a little (sub-mm/s): motion starts when the
  // speed changes by far more in one step than it ever does at rest.
  const std::size_t settled = samples_.size();
  ASSERT_TRUE(step(48));
  double rest_jitter = 0;  // largest step-to-step speed change at rest (m/s)
  for (std::size_t i = settled + 1; i < samples_.size(); ++i)
    rest_jitter = std::max(rest_jitter, std::abs(samples_[i].speed[0] - samples_[i - 1].speed[0]));
  const double threshold = std::max(1e-3, 5 * rest_jitter);
  const double rest_speed = samples_.back().speed[0];

  ASSERT_TRUE(send_and_wait(0, 1.0));
  const auto& command = forwarded_[0].back();
  EXPECT_NEAR(command.t_received, now_, kEps);  // stamped with the latest SIM_STATE's time
  EXPECT_NEAR(command.t_apply - command.t_received, latency, kEps);
  const std::size_t before = samples_.size();
  for (int i = 0; i < latency_steps + 6; ++i) ASSERT_TRUE(step(1));

  double t_motion = -1;
  for (std::size_t i = before; i < samples_.size() && t_motion < 0; ++i)
    if (samples_[i].speed[0] - rest_speed > threshold) t_motion = samples_[i].t;
  ASSERT_GT(t_motion, 0) << "the robot never moved";
  const double delay = t_motion - command.t_received;
  EXPECT_GE(delay, latency - kEps);
  EXPECT_LE(delay, latency + kStep + kEps);
  EXPECT_LT(speed_at(1, t_motion), 0.01);  // the other team's robot did not move
  std::cout << "command -> motion: " << delay * 1e3 << " ms (radio latency " << latency * 1e3
            << " ms, step " << kStep * 1e3 << " ms; motion = speed up by " << threshold
            << " m/s, at rest it changes by at most " << rest_jitter << " m/s per step)\n";
}

// Issue: a robot whose commands stop halts after the configured timeout; a team
// sending at 20 Hz keeps moving at full commanded speed while the other team
// sends nothing; each team's timeout is its own.
TEST_F(RadioPhysicsTest, EachTeamsRobotsHaltAfterTheirOwnCommandTimeout) {
  const double speed = 0.5;                               // m/s
  const double yellow_timeout = 0.1, blue_timeout = 0.4;  // s; yellow's is 2 x its 20 Hz period
  start(exact_profile(8, yellow_timeout), exact_profile(8, blue_timeout));
  ASSERT_TRUE(step(120));
  // Both teams drive at 20 Hz (every 12 steps) for 1.5 s; then blue goes
  // silent while yellow sends on until 3.5 s; then yellow goes silent too.
  const double t0 = now_;
  double blue_stops = -1, yellow_stops = -1;  // t_apply of each team's last command
  while (now_ < t0 + 4.5) {
    const double t = now_ - t0;
    if (t < 3.5 - kEps) {
      ASSERT_TRUE(send_and_wait(0, speed));
      yellow_stops = forwarded_[0].back().t_apply;
    }
    if (t < 1.5 - kEps) {
      ASSERT_TRUE(send_and_wait(1, speed));
      blue_stops = forwarded_[1].back().t_apply;
    }
    ASSERT_TRUE(step(12));
  }
  // Yellow at full commanded speed from 1 s on, all through blue's silence.
  for (const auto& s : samples_) {
    if (s.t < t0 + 1.0 || s.t > yellow_stops) continue;
    ASSERT_NEAR(s.speed[0], speed, 0.05 * speed) << "yellow at t=" << s.t - t0;
  }
  // Blue keeps its last command until its timeout, then stops.
  EXPECT_NEAR(speed_at(1, blue_stops + blue_timeout - 2 * kStep), speed, 0.05 * speed);
  const double blue_halt = first_below(1, blue_stops, 0.95 * speed);
  EXPECT_GE(blue_halt, blue_stops + blue_timeout);
  EXPECT_LE(blue_halt, blue_stops + blue_timeout + 0.03);
  EXPECT_LT(speed_at(1, blue_stops + blue_timeout + 0.5), 0.02);
  // Yellow stops after its own, shorter timeout.
  const double yellow_halt = first_below(0, yellow_stops, 0.95 * speed);
  EXPECT_GE(yellow_halt, yellow_stops + yellow_timeout);
  EXPECT_LE(yellow_halt, yellow_stops + yellow_timeout + 0.03);
  EXPECT_LT(speed_at(0, yellow_stops + yellow_timeout + 0.5), 0.02);
  std::cout << "halt after last command: yellow " << (yellow_halt - yellow_stops) * 1e3
            << " ms (timeout " << yellow_timeout * 1e3 << "), blue "
            << (blue_halt - blue_stops) * 1e3 << " ms (timeout " << blue_timeout * 1e3 << ")\n";
}
