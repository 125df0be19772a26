#include "ball.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "fit.hpp"

namespace ubersim::report {
namespace {

constexpr double kAtRest = 0.005;     // m/s: slower counts as stopped (5 um of roll left)
constexpr double kFireTimeout = 1.0;  // s: the kicker must have fired by then
constexpr double kGap = 0.002;        // m between ball and kicker face (within KICKER_REACH)
constexpr double kAirborne = 0.002;   // m above its resting height: the chip has left the carpet

double horizontal_speed(const BallSample& b) {
  return std::hypot(b.vx, b.vy);
}

radio_packet_t kick_packet(double t_sent, double kick, double chip, double angle) {
  radio_packet_t packet{};
  packet.t_sent = t_sent;
  robot_command_t c{};
  c.robot_id = kRobot;
  c.mode = robot_command_t::MODE_LOCAL_VELOCITY;
  c.kick_speed = kick;
  c.chip_speed = chip;
  c.chip_angle = angle;
  packet.commands.push_back(c);
  return packet;
}

// Puts the robot at the hall's start, still, with the ball resting against its kicker.
void set_up_kick(SimRig& rig, const RobotTypeConfig& robot, double ball_radius) {
  send_stop(rig, kRobot);
  const double x = ExperimentSetup::kHallStartX;
  sim_control_t request = place_robot(kRobot, x, 0, 0);
  place_ball(request, x + robot.front_distance + ball_radius + kGap, 0, 0, 0, 0, 0);
  rig.place(request);
  rig.step(12);
}

// Sends the kick until the ball moves; returns the index of the first moving sample.
std::size_t fire(SimRig& rig, const std::vector<BallSample>& balls, double kick, double chip,
                 double angle, double ball_radius) {
  const double deadline = rig.time() + kFireTimeout;
  const std::size_t from = balls.size();
  while (rig.time() < deadline) {
    rig.send(kick_packet(rig.time(), kick, chip, angle));
    rig.step(kStepsPerCommand);
    for (std::size_t i = std::max<std::size_t>(from, 1); i < balls.size(); ++i) {
      if (horizontal_speed(balls[i]) > 0.1 || balls[i].z > ball_radius + 1e-3) {
        rig.send(kick_packet(rig.time(), 0, 0, 0));  // fired: stop asking
        return i;
      }
    }
  }
  throw std::runtime_error("the kicker did not fire within " + std::to_string(kFireTimeout) + " s");
}

double fitted_deceleration(const std::vector<RollSample>& samples, double begin, double end) {
  std::vector<double> t, v;
  for (const auto& s : samples) {
    if (s.t < begin || s.t > end) continue;
    t.push_back(s.t);
    v.push_back(s.v);
  }
  return -fit_line(t, v).slope;
}

}  // namespace

BallResult run_ball(const ExperimentSetup& setup, const BallSettings& settings) {
  BallResult result;
  result.settings = settings;
  result.ball_config = setup.ball();
  result.gravity = setup.gravity();
  const RobotTypeConfig robot = setup.robot(settings.robot_type);
  const physics::BallConfig& ball = setup.ball();
  const double g = setup.gravity();

  RigOptions options;
  options.name = "ball";
  options.scenario = setup.hall_scenario(settings.robot_type);
  options.vision_profile = settings.vision_profile;
  options.radio_profile = settings.radio_profile;
  options.vision_seed = options.radio_seed = settings.seed;
  SimRig rig(setup.paths(), options);
  std::vector<BallSample> balls;
  rig.on_state([&](const sim_state_t& s) { balls.push_back(ball_sample(s)); });

  for (const double speed : settings.kick_speeds) {
    set_up_kick(rig, robot, ball.radius);
    balls.clear();
    const std::size_t first = fire(rig, balls, speed, 0, 0, ball.radius);
    KickResult kick;
    kick.commanded = speed;
    kick.model = predict_roll_out(ball, speed);
    const BallSample start = balls[first - 1];  // the kick happens in the step after it
    kick.launch_speed = horizontal_speed(balls[first]);
    const double limit = start.t + 1.5 * kick.model.time + 2.0;
    while (horizontal_speed(balls.back()) >= kAtRest && rig.time() < limit) rig.step(24);

    kick.time = -1;
    for (std::size_t i = first - 1; i < balls.size(); ++i) {
      const BallSample& b = balls[i];
      const RollSample s{b.t - start.t, std::hypot(b.x - start.x, b.y - start.y),
                         horizontal_speed(b)};
      kick.trajectory.push_back(s);
      if (i > first && s.v < kAtRest) {
        kick.time = s.t;
        kick.distance = s.s;
        break;
      }
    }
    if (kick.time < 0) {
      throw std::runtime_error("ball kicked at " + std::to_string(speed) +
                               " m/s still moving after " + std::to_string(limit - start.t) + " s");
    }
    const double slide = kick.model.slide_time;
    const double roll = kick.model.time - slide;
    kick.sliding_deceleration = fitted_deceleration(kick.trajectory, 0.2 * slide, 0.8 * slide);
    kick.rolling_deceleration =
        fitted_deceleration(kick.trajectory, slide + 0.2 * roll, slide + 0.8 * roll);
    result.kicks.push_back(std::move(kick));
  }

  for (const double speed : settings.chip_speeds) {
    set_up_kick(rig, robot, ball.radius);
    balls.clear();
    const std::size_t first = fire(rig, balls, 0, speed, settings.chip_angle, ball.radius);
    ChipResult chip;
    chip.commanded = speed;
    chip.angle = settings.chip_angle;
    chip.model = predict_chip(speed, settings.chip_angle, g);
    const BallSample start = balls[first - 1];
    const double until = start.t + chip.model.flight_time + 0.5;
    while (rig.time() < until) rig.step(kStepsPerCommand);

    bool airborne = false, landed = false;
    for (std::size_t i = first; i < balls.size(); ++i) {
      const BallSample& b = balls[i];
      const BallSample& before = balls[i - 1];
      chip.trajectory.push_back(
          {b.t - start.t, std::hypot(b.x - start.x, b.y - start.y), b.z - ball.radius});
      if (landed) continue;
      chip.peak = std::max(chip.peak, b.z - start.z);
      const bool was_airborne = airborne;
      airborne = airborne || b.z > start.z + kAirborne;
      // Touchdown: in the air and falling before, now at the carpet or bounced up again.
      if (was_airborne && before.vz < 0 && (b.vz >= 0 || b.z <= start.z)) {
        // Where the ballistic arc from `before` meets the starting height.
        const double drop = std::max(0.0, before.z - start.z);
        const double tau = (before.vz + std::sqrt(before.vz * before.vz + 2 * g * drop)) / g;
        const double d0 = std::hypot(before.x - start.x, before.y - start.y);
        chip.distance = d0 + std::hypot(before.vx, before.vy) * tau;
        landed = true;
      }
    }
    if (!landed) {
      throw std::runtime_error("chip at " + std::to_string(speed) + " m/s never landed");
    }
    result.chips.push_back(std::move(chip));
  }
  const std::string problems = rig.stop();
  if (!problems.empty()) throw std::runtime_error(problems);
  return result;
}

}  // namespace ubersim::report
