#include "acceleration.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "fit.hpp"

namespace ubersim::report {
namespace {

constexpr double kStartX = -5.5;  // m, where drive_scenario puts the robot
constexpr double kSettle = 0.1;   // s: a jointed robot comes to rest on its wheels

// Records the yellow robot's ground truth and detections while it is in scope.
struct Recorder {
  std::vector<RobotSample> truth;
  std::vector<RobotDetection> vision;
  explicit Recorder(SimRig& rig) {
    rig.on_state([this](const sim_state_t& s) {
      RobotSample r;
      if (find_robot(s, kRobot, r)) truth.push_back(r);
    });
    rig.on_frame([this](const vision_frame_t& f) {
      RobotDetection d;
      if (find_detection(f, kRobot, d)) vision.push_back(d);
    });
  }
};

// Ground truth and detections from t0 on, along the heading the robot had at t0.
void project(const std::vector<RobotSample>& truth, const std::vector<RobotDetection>& vision,
             double t0, std::vector<TrajectorySample>& truth_out,
             std::vector<TrajectorySample>& vision_out, double* sideways = nullptr) {
  auto start = std::find_if(truth.begin(), truth.end(),
                            [&](const RobotSample& r) { return r.t >= t0 - 1e-9; });
  if (start == truth.end()) throw std::runtime_error("no ground truth after the start");
  const double ux = std::cos(start->heading), uy = std::sin(start->heading);
  const double x0 = start->x, y0 = start->y;
  double drift = 0;
  for (auto it = start; it != truth.end(); ++it) {
    const double dx = it->x - x0, dy = it->y - y0;
    truth_out.push_back({it->t - t0, dx * ux + dy * uy, it->vx * ux + it->vy * uy});
    drift = std::max(drift, std::abs(-dx * uy + dy * ux));
  }
  if (sideways != nullptr) *sideways = drift;
  for (const auto& d : vision) {
    if (d.t < t0 - 1e-9) continue;
    vision_out.push_back({d.t - t0, (d.x - x0) * ux + (d.y - y0) * uy, 0});
  }
  // Speed from VISION as a team would estimate it: central difference.
  for (std::size_t i = 0; i < vision_out.size(); ++i) {
    const std::size_t a = i == 0 ? 0 : i - 1;
    const std::size_t b = std::min(i + 1, vision_out.size() - 1);
    if (b > a) {
      vision_out[i].v = (vision_out[b].s - vision_out[a].s) / (vision_out[b].t - vision_out[a].t);
    }
  }
}

double fit_speed_slope(const std::vector<TrajectorySample>& samples, double begin, double end) {
  std::vector<double> t, v;
  for (const auto& s : samples) {
    if (s.t < begin || s.t > end) continue;
    t.push_back(s.t);
    v.push_back(s.v);
  }
  return fit_line(t, v).slope;
}

// Acceleration from positions (VISION): twice the curvature of a quadratic fit,
// with its standard error. NaN when the window holds too few frames.
struct Estimate {
  double value = std::numeric_limits<double>::quiet_NaN();
  double standard_error = std::numeric_limits<double>::quiet_NaN();
};
Estimate fit_position_curvature(const std::vector<TrajectorySample>& samples, double begin,
                                double end) {
  std::vector<double> t, s;
  for (const auto& p : samples) {
    if (p.t < begin || p.t > end) continue;
    t.push_back(p.t);
    s.push_back(p.s);
  }
  const QuadraticFit fit = fit_quadratic(t, s);
  Estimate e;
  if (fit.points >= 6) {
    e.value = 2 * fit.c2;
    e.standard_error = 2 * fit.c2_standard_error;
  }
  return e;
}

radio_packet_t forward_command(double t_sent, double speed) {
  radio_packet_t packet{};
  packet.t_sent = t_sent;
  robot_command_t c{};
  c.robot_id = kRobot;
  c.mode = robot_command_t::MODE_LOCAL_VELOCITY;
  c.vx = speed;
  packet.commands.push_back(c);
  return packet;
}

radio_packet_t wheel_command(double t_sent, double speed, const RobotTypeConfig& robot) {
  radio_packet_t packet{};
  packet.t_sent = t_sent;
  robot_command_t c{};
  c.robot_id = kRobot;
  c.mode = robot_command_t::MODE_WHEEL_SPEEDS;
  // Inverse kinematics for straight ahead: wheel i turns at d_i . (v, 0) / r.
  for (const auto& w : robot.wheels)
    c.wheel_speeds.push_back(w.drive_x * speed / robot.wheel_radius);
  packet.commands.push_back(c);
  return packet;
}

}  // namespace

TrajectorySample ideal_ramp(const RampResult& ramp, double t) {
  const double a = ramp.settings.acceleration;
  const double top = ramp.prediction.top_speed;
  const double moving = std::max(0.0, t - ramp.command_delay);
  const double ramp_time = top / a;
  if (moving <= ramp_time) return {t, a * moving * moving / 2, a * moving};
  return {t, top * ramp_time / 2 + top * (moving - ramp_time), top};
}

RampResult run_ramp(const ExperimentSetup& setup, const RampSettings& settings) {
  RampResult result;
  result.settings = settings;
  const RobotTypeConfig robot = setup.robot(settings.robot_type);
  result.prediction = predict_forward_drive(robot, setup.gravity());
  const double a = settings.acceleration;
  const double ramp_time = result.prediction.top_speed / a;
  const std::string scenario = setup.drive_scenario(settings.robot_type);
  const double latency = setup.radio_latency(settings.radio_profile);

  for (int k = 0; k < settings.trials; ++k) {
    RigOptions options;
    options.name = "ramp_" + settings.robot_type + "_" + std::to_string(k);
    options.scenario = scenario;
    options.vision_profile = settings.vision_profile;
    options.radio_profile = settings.radio_profile;
    options.vision_seed = options.radio_seed = settings.first_seed + static_cast<std::uint64_t>(k);
    SimRig rig(setup.paths(), options);
    Recorder record(rig);
    rig.step(static_cast<int>(std::lround(kSettle / rig.dt())));
    result.command_delay = latency + rig.dt();
    result.window_begin = result.command_delay + 0.1 * ramp_time;
    result.window_end = result.command_delay + 0.9 * ramp_time;
    const double duration = result.command_delay + ramp_time + settings.hold;

    const double t0 = rig.time();
    while (rig.time() - t0 < duration - 1e-9) {
      rig.send(forward_command(rig.time(), a * (rig.time() - t0)));
      rig.step(kStepsPerCommand);
    }
    const std::string problems = rig.stop();
    if (!problems.empty()) throw std::runtime_error(problems);

    RampTrial trial;
    trial.seed = options.vision_seed;
    project(record.truth, record.vision, t0, trial.truth, trial.vision, &trial.sideways_drift);
    trial.truth_acceleration = fit_speed_slope(trial.truth, result.window_begin, result.window_end);
    const Estimate vision =
        fit_position_curvature(trial.vision, result.window_begin, result.window_end);
    trial.vision_acceleration = vision.value;
    trial.vision_standard_error = vision.standard_error;
    std::vector<double> end_speeds;
    for (const auto& s : trial.truth) {
      if (s.t >= duration - 0.2) end_speeds.push_back(s.v);
    }
    trial.top_speed = mean(end_speeds);
    result.trials.push_back(std::move(trial));
  }
  return result;
}

SweepResult run_sweep(const ExperimentSetup& setup, const SweepSettings& settings) {
  SweepResult result;
  result.settings = settings;
  const RobotTypeConfig robot = setup.robot(settings.robot_type);
  const DrivePrediction& p = result.prediction = predict_forward_drive(robot, setup.gravity());
  result.speed_window_high = 0.6 * p.top_speed;
  result.speed_window_low = 0.25 * result.speed_window_high;
  const double latency = setup.radio_latency(settings.radio_profile);

  RigOptions options;
  options.name = "sweep_" + settings.robot_type;
  options.scenario = setup.drive_scenario(settings.robot_type);
  options.vision_profile = settings.vision_profile;
  options.radio_profile = settings.radio_profile;
  options.vision_seed = options.radio_seed = settings.seed;
  SimRig rig(setup.paths(), options);
  Recorder record(rig);

  for (const bool wheels : {true, false}) {
    if (!wheels && !settings.velocity_commands_too) continue;
    for (const double fraction : settings.fractions) {
      SweepPoint point;
      point.wheel_speeds = wheels;
      point.commanded = fraction * p.acceleration;
      // Still, then put back at the start.
      send_stop(rig, kRobot);
      rig.place(place_robot(kRobot, kStartX, 0, 0));
      rig.step(static_cast<int>(std::lround(kSettle / rig.dt())));
      record.truth.clear();
      record.vision.clear();

      double achievable = std::min(point.commanded, p.acceleration);
      if (!wheels && p.onboard_limit > 0) achievable = std::min(achievable, p.onboard_limit);
      const double limit_time = latency + 1.5 * result.speed_window_high / achievable + 0.3;
      const double t0 = rig.time();
      while (rig.time() - t0 < limit_time &&
             (record.truth.empty() || record.truth.back().vx < 1.05 * result.speed_window_high)) {
        const double speed = point.commanded * (rig.time() - t0);
        rig.send(wheels ? wheel_command(rig.time(), std::min(speed, p.motor_top_speed), robot)
                        : forward_command(rig.time(), std::min(speed, p.top_speed)));
        rig.step(kStepsPerCommand);
      }
      std::vector<TrajectorySample> truth, vision;
      project(record.truth, record.vision, t0, truth, vision);
      // Fit where the robot's own speed is inside the window.
      double begin = -1, end = -1;
      for (const auto& s : truth) {
        if (begin < 0 && s.v >= result.speed_window_low) begin = s.t;
        if (end < 0 && s.v >= result.speed_window_high) end = s.t;
      }
      // A robot that never reaches the window (it spins out, say) is measured
      // over what it did: the point then shows how far off it is.
      point.reached_window = begin >= 0 && end > begin;
      if (begin < 0) begin = 0;
      if (end <= begin) end = truth.empty() ? 0 : truth.back().t;
      point.truth = fit_speed_slope(truth, begin, end);
      const Estimate seen = fit_position_curvature(vision, begin, end);
      point.vision = seen.value;
      point.vision_standard_error = seen.standard_error;
      result.points.push_back(point);
    }
  }
  const std::string problems = rig.stop();
  if (!problems.empty()) throw std::runtime_error(problems);

  std::vector<double> saturated;
  for (const auto& point : result.points) {
    if (point.wheel_speeds && point.commanded >= 1.3 * p.acceleration) {
      saturated.push_back(point.truth);
    }
  }
  result.saturation = mean(saturated);
  return result;
}

}  // namespace ubersim::report
