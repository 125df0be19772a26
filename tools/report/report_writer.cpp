#include "report_writer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <stdexcept>

#include "fit.hpp"
#include "ubersim/config.hpp"
#include "ubersim/config_paths.hpp"

namespace ubersim::report {
namespace {

std::ofstream open(const std::string& dir, const std::string& name) {
  std::ofstream out(std::filesystem::path(dir) / name);
  if (!out) throw std::runtime_error("cannot write " + name + " in " + dir);
  return out;
}

// A value for gnuplot: '?' (missing) when not finite.
std::string number(double value) {
  return std::isfinite(value) ? fmt::format("{:.5f}", value) : std::string("?");
}

std::string percent(double relative) {
  return fmt::format("{:+.1f} %", 100 * relative);
}
const char* verdict(bool met) {
  return met ? "met" : "**MISSED**";
}

const Check* worst(const std::vector<Check>& checks) {
  const Check* w = nullptr;
  for (const auto& c : checks) {
    if (w == nullptr || !c.met() > !w->met() ||
        (c.met() == w->met() && std::abs(c.error()) > std::abs(w->error()))) {
      w = &c;
    }
  }
  return w;
}

int count_missed(const std::vector<Check>& checks) {
  return static_cast<int>(
      std::count_if(checks.begin(), checks.end(), [](const Check& c) { return !c.met(); }));
}

double profile_value(const ExperimentSetup& setup, const char* kind, const std::string& profile,
                     const char* key) {
  return ConfigFile::load(resolve_config(setup.paths().config_dir, kind, profile)).real(key);
}

std::vector<Check> filter(const std::vector<Check>& checks, const std::string& contains) {
  std::vector<Check> out;
  for (const auto& c : checks) {
    if (c.what.find(contains) != std::string::npos) out.push_back(c);
  }
  return out;
}

void write_ramp_data(const std::string& dir, const std::vector<RampResult>& ramps,
                     std::ostream& values) {
  values << fmt::format("ramp_count = {}\n", ramps.size());
  for (std::size_t i = 0; i < ramps.size(); ++i) {
    const RampResult& r = ramps[i];
    const std::string type = r.settings.robot_type;
    values << fmt::format("ramp_type{} = \"{}\"\nramp_top{} = {:.6g}\nramp_acc{} = {:.6g}\n", i,
                          type, i, r.prediction.top_speed, i, r.settings.acceleration);
    values << fmt::format("ramp_delay{} = {:.6g}\n", i, r.command_delay);
    auto truth = open(dir, "ramp_" + type + "_truth.dat");
    auto vision = open(dir, "ramp_" + type + "_vision.dat");
    auto ideal = open(dir, "ramp_" + type + "_ideal.dat");
    truth << "# t (s since the first command)  s (m along the start heading)  v (m/s); one block "
             "per trial\n";
    vision << "# t (s, capture time since the first command)  s (m)  v (m/s, central "
              "difference); one block per trial\n";
    ideal << "# t (s)  s (m)  v (m/s): constant acceleration from the command delay, saturating "
             "at the predicted top speed\n";
    double end = 0;
    for (const auto& trial : r.trials) {
      truth << "# seed " << trial.seed << "\n";
      for (const auto& s : trial.truth) {
        truth << fmt::format("{:.5f} {:.6f} {:.6f}\n", s.t, s.s, s.v);
      }
      truth << "\n\n";
      vision << "# seed " << trial.seed << "\n";
      for (const auto& s : trial.vision) {
        vision << fmt::format("{:.5f} {:.6f} {:.6f}\n", s.t, s.s, s.v);
      }
      vision << "\n\n";
      if (!trial.truth.empty()) end = std::max(end, trial.truth.back().t);
    }
    const double step = 1.0 / 240;
    const auto steps = static_cast<int>(std::ceil(end / step));
    for (int k = 0; k <= steps; ++k) {
      const TrajectorySample s = ideal_ramp(r, k * step);
      ideal << fmt::format("{:.5f} {:.6f} {:.6f}\n", s.t, s.s, s.v);
    }
  }
}

void write_sweep_data(const std::string& dir, const std::vector<SweepResult>& sweeps,
                      std::ostream& values) {
  values << fmt::format("sweep_count = {}\n", sweeps.size());
  for (std::size_t i = 0; i < sweeps.size(); ++i) {
    const SweepResult& s = sweeps[i];
    const std::string type = s.settings.robot_type;
    values << fmt::format(
        "sweep_type{} = \"{}\"\nsweep_pred{} = {:.6g}\nsweep_onboard{} = {:.6g}\n"
        "sweep_torque{} = {:.6g}\nsweep_traction{} = {:.6g}\n",
        i, type, i, s.prediction.acceleration, i, s.prediction.onboard_limit, i,
        s.prediction.torque_limited, i, s.prediction.traction_limited);
    auto out = open(dir, "sweep_" + type + ".dat");
    out << "# commanded (m/s^2)  achieved, ground truth (m/s^2)  achieved, VISION (m/s^2)  its "
           "standard error (m/s^2); '?' = too few frames; block 0 wheel-speed commands, block 1 "
           "velocity commands\n";
    for (const bool wheels : {true, false}) {
      for (const auto& p : s.points) {
        if (p.wheel_speeds != wheels) continue;
        out << fmt::format("{:.5f} {:.5f} {} {}\n", p.commanded, p.truth, number(p.vision),
                           number(p.vision_standard_error));
      }
      out << "\n\n";
    }
  }
}

void write_figure8_data(const std::string& dir, const std::vector<Figure8Result>& figure8,
                        std::ostream& values) {
  values << fmt::format("figure8_count = {}\n", figure8.size());
  for (std::size_t i = 0; i < figure8.size(); ++i) {
    const Figure8Result& f = figure8[i];
    const std::string label = f.settings.label;
    values << fmt::format("figure8_label{} = \"{}\"\nfigure8_period{} = {:.6g}\n", i, label, i,
                          f.period);
    auto truth = open(dir, "figure8_" + label + "_truth.dat");
    auto vision = open(dir, "figure8_" + label + "_vision.dat");
    auto error = open(dir, "figure8_" + label + "_error.dat");
    truth << "# t (s)  x (m)  y (m): ground truth, every step\n";
    vision << "# t (s, capture)  x (m)  y (m): VISION detections\n";
    error << "# t (s)  tracking error (m, to the reference at the same time)  path error (m, to "
             "the nearest point of the curve)\n";
    for (std::size_t k = 0; k < f.truth.size(); ++k) {
      const PathSample& p = f.truth[k];
      const PathSample& ref = f.reference[k];
      truth << fmt::format("{:.5f} {:.6f} {:.6f}\n", p.t, p.x, p.y);
      double nearest = 1e9;
      for (const auto& c : f.path) nearest = std::min(nearest, std::hypot(c.x - p.x, c.y - p.y));
      error << fmt::format("{:.5f} {:.6f} {:.6f}\n", p.t, std::hypot(p.x - ref.x, p.y - ref.y),
                           nearest);
    }
    for (const auto& p : f.vision) vision << fmt::format("{:.5f} {:.6f} {:.6f}\n", p.t, p.x, p.y);
  }
  if (!figure8.empty()) {
    auto path = open(dir, "figure8_path.dat");
    path << "# x (m)  y (m): the intended figure-8, one lap\n";
    const auto& curve = figure8.front().path;
    for (std::size_t i = 0; i < curve.size(); i += 4) {  // 1000 points draw it smoothly
      path << fmt::format("{:.6f} {:.6f}\n", curve[i].x, curve[i].y);
    }
    path << fmt::format("{:.6f} {:.6f}\n", figure8.front().path.front().x,
                        figure8.front().path.front().y);
  }
}

void write_ball_data(const std::string& dir, const BallResult& ball) {
  auto kicks = open(dir, "kicks.dat");
  kicks << "# commanded (m/s)  distance (m)  model distance (m)  time (s)  model time (s)\n";
  auto trajectories = open(dir, "kick_trajectories.dat");
  trajectories << "# t (s since the kick)  s (m)  v (m/s); one block per kick\n";
  for (const auto& k : ball.kicks) {
    kicks << fmt::format("{:.3f} {:.5f} {:.5f} {:.5f} {:.5f}\n", k.commanded, k.distance,
                         k.model.distance, k.time, k.model.time);
    trajectories << "# kick " << k.commanded << " m/s\n";
    // Every 6th step is plenty for a curve that lasts seconds.
    for (std::size_t i = 0; i < k.trajectory.size(); i += 6) {
      const auto& s = k.trajectory[i];
      trajectories << fmt::format("{:.5f} {:.5f} {:.5f}\n", s.t, s.s, s.v);
    }
    trajectories << "\n\n";
  }
  auto model = open(dir, "kick_model.dat");
  model << "# t (s)  s (m)  v (m/s): the config's sliding/rolling model; one block per kick\n";
  for (const auto& k : ball.kicks) {
    const auto points = static_cast<int>(std::ceil((k.model.time + 0.05) / 0.02));
    for (int i = 0; i <= points; ++i) {
      const double t = 0.02 * i;
      model << fmt::format("{:.4f} {:.5f} {:.5f}\n", t,
                           roll_out_distance(ball.ball_config, k.commanded, t),
                           roll_out_speed(ball.ball_config, k.commanded, t));
    }
    model << "\n\n";
  }
  auto chips = open(dir, "chips.dat");
  chips << "# commanded (m/s)  angle (rad)  distance (m)  ballistic (m)  peak (m)  ballistic "
           "peak (m)\n";
  auto chip_paths = open(dir, "chip_trajectories.dat");
  chip_paths << "# d (m, horizontal from the launch)  z (m, ball bottom above the carpet); "
                "one block per chip\n";
  auto chip_model = open(dir, "chip_model.dat");
  chip_model << "# d (m)  z (m): ballistic arcs; one block per chip\n";
  for (const auto& c : ball.chips) {
    chips << fmt::format("{:.3f} {:.5f} {:.5f} {:.5f} {:.5f} {:.5f}\n", c.commanded, c.angle,
                         c.distance, c.model.distance, c.peak, c.model.peak_height);
    chip_paths << "# chip " << c.commanded << " m/s\n0 0\n";
    for (const auto& s : c.trajectory) chip_paths << fmt::format("{:.5f} {:.5f}\n", s.d, s.z);
    chip_paths << "\n\n";
    const double along = c.commanded * std::cos(c.angle);
    const double up = c.commanded * std::sin(c.angle);
    for (int i = 0; i <= 100; ++i) {
      const double t = c.model.flight_time * i / 100;
      chip_model << fmt::format("{:.5f} {:.5f}\n", along * t,
                                std::max(0.0, up * t - ball.gravity * t * t / 2));
    }
    chip_model << "\n\n";
  }
}

}  // namespace

void write_data_files(const std::string& dir, const FidelityResults& results) {
  std::filesystem::create_directories(dir);
  auto values = open(dir, "values.gp");
  values << "# Predictions from the config files (written by ubersim_report_fidelity)\n";
  write_ramp_data(dir, results.ramps, values);
  write_sweep_data(dir, results.sweeps, values);
  write_figure8_data(dir, results.figure8, values);
  for (const auto& ball : results.ball) write_ball_data(dir, ball);
}

namespace {

CheckGroup group(std::vector<Check> checks) {
  CheckGroup g;
  if (const Check* w = worst(checks)) g.worst = *w;
  g.missed = count_missed(checks);
  g.checks = std::move(checks);
  return g;
}

bool contains(const Check& check, const std::string& text) {
  return check.what.find(text) != std::string::npos;
}

RampVerdict decide_ramp(const RampResult& ramp, const Tolerances& tolerances) {
  RampVerdict v;
  v.checks = check_ramp(ramp, tolerances);
  v.acceleration = group(filter(v.checks, "acceleration"));
  v.top_speed = group(filter(v.checks, "top speed"));
  return v;
}

SweepVerdict decide_sweep(const SweepResult& sweep, const Tolerances& tolerances) {
  SweepVerdict v;
  v.checks = check_sweep(sweep, tolerances);
  v.saturation = filter(v.checks, "saturation").front();
  std::vector<Check> below;
  for (const auto& c : v.checks) {
    if (!contains(c, "saturation")) below.push_back(c);
  }
  v.below_saturation = group(std::move(below));
  return v;
}

// Relative errors of two measured figures against their model, and whether
// both are within `tolerance`.
PairVerdict decide_pair(double first, double first_model, double second, double second_model,
                        double tolerance) {
  PairVerdict v;
  v.first_error = (first - first_model) / first_model;
  v.second_error = (second - second_model) / second_model;
  v.met = std::abs(v.first_error) <= tolerance && std::abs(v.second_error) <= tolerance;
  return v;
}

BallVerdict decide_ball(const BallResult& ball, const Tolerances& tolerances) {
  BallVerdict v;
  v.checks = check_ball(ball, tolerances);
  for (const auto& k : ball.kicks) {
    v.kicks.push_back(
        decide_pair(k.distance, k.model.distance, k.time, k.model.time, tolerances.roll_out));
  }
  for (const auto& c : ball.chips) {
    v.chips.push_back(
        decide_pair(c.distance, c.model.distance, c.peak, c.model.peak_height, tolerances.chip));
  }
  return v;
}

// The targets table's rows, each over the checks of all experiments it covers.
std::vector<TargetRow> decide_targets(const std::vector<Check>& ramp_checks,
                                      const std::vector<Check>& sweep_checks,
                                      const std::vector<Check>& ball_checks) {
  std::vector<Check> below_saturation, saturation;
  for (const auto& c : sweep_checks) {
    (contains(c, "saturation") ? saturation : below_saturation).push_back(c);
  }
  auto truth_accel = filter(ramp_checks, "ground truth");
  truth_accel.insert(truth_accel.end(), below_saturation.begin(), below_saturation.end());
  return {
      {"Acceleration within 5 % of commanded until the predicted saturation "
       "(ground truth: 2 m/s^2 ramps and the slower sweep ramps)",
       group(truth_accel)},
      {"The same, from VISION (2 m/s^2 ramps, vision noise on)",
       group(filter(ramp_checks, "VISION"))},
      {"Top speed within 10 % of the config's", group(filter(ramp_checks, "top speed"))},
      {"Saturation (torque/traction) within 10 % of the prediction", group(saturation)},
      {"Ball roll-out distance and time within 10 % of the model",
       group(filter(ball_checks, "roll-out"))},
      {"Chip flight distance and peak height within 10 % of ballistic",
       group(filter(ball_checks, "chip"))},
  };
}

// One summary row over a group of checks: the worst error and how many missed.
std::string summary_row(const TargetRow& row) {
  const CheckGroup& g = row.group;
  if (g.checks.empty()) return "";
  return fmt::format("| {} | worst {} ({}) | {} of {} checks met | {} |\n", row.target,
                     percent(g.worst->error()), g.worst->what, g.checks.size() - g.missed,
                     g.checks.size(), verdict(g.met()));
}

std::string worst_error(const CheckGroup& g) {
  return g.worst ? percent(g.worst->error()) : "-";
}

void write_acceleration(std::ostream& md, const FidelityResults& results,
                        const FidelityVerdicts& verdicts, const ExperimentSetup& setup) {
  const RampSettings& s = results.ramps.front().settings;
  md << "## 1. Acceleration (the paper's Figure 7)\n\n";
  md << fmt::format(
      "Each robot type, from rest, is sent forward-velocity commands that rise at {:g} m/s^2 "
      "(a `radio_packet_t` on `RADIO_YELLOW` every 1/60 s, through the real `ubersim_radio` "
      "with the `{}` link) and held on past its top speed; its trajectory is read back from "
      "`VISION` (the real `ubersim_vision`, profile `{}`: noise on) and from ground truth "
      "(`SIM_STATE`). {} trials per type, each with its own vision and radio seed. The "
      "acceleration is fitted over 10-90 % of the ramp up to the predicted top speed: from "
      "ground truth as the slope of the speed, from VISION as the curvature of the position "
      "(a quadratic fit). The ideal curve starts one radio latency plus one physics step "
      "after the first command.\n\n",
      s.acceleration, s.radio_profile, s.vision_profile, s.trials);
  md << "| robot type | model | commanded | ground truth: mean (min .. max) | VISION: mean "
        "(sd) | worst error | target | |\n|---|---|---|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < results.ramps.size(); ++i) {
    const RampResult& r = results.ramps[i];
    std::vector<double> truth, vision;
    for (const auto& t : r.trials) {
      truth.push_back(t.truth_acceleration);
      vision.push_back(t.vision_acceleration);
    }
    const CheckGroup& accel = verdicts.ramps[i].acceleration;
    const RobotTypeConfig robot = setup.robot(r.settings.robot_type);
    md << fmt::format(
        "| {} | {} | {:.2f} m/s^2 | {:.3f} ({:.3f} .. {:.3f}) m/s^2 | {:.3f} ({:.3f}) m/s^2 | {} "
        "| ±5 % | {} |\n",
        r.settings.robot_type, enum_name(robot.model, kDriveModelNames), r.settings.acceleration,
        mean(truth), *std::min_element(truth.begin(), truth.end()),
        *std::max_element(truth.begin(), truth.end()), mean(vision), standard_deviation(vision),
        worst_error(accel), verdict(accel.met()));
  }
  md << "\n| robot type | top speed measured (mean of trials) | predicted | limited by | error | "
        "target | |\n|---|---|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < results.ramps.size(); ++i) {
    const RampResult& r = results.ramps[i];
    std::vector<double> top;
    for (const auto& t : r.trials) top.push_back(t.top_speed);
    const CheckGroup& top_speed = verdicts.ramps[i].top_speed;
    md << fmt::format("| {} | {:.3f} m/s | {:.3f} m/s | {} | {} | ±10 % | {} |\n",
                      r.settings.robot_type, mean(top), r.prediction.top_speed,
                      r.prediction.top_speed_limited_by, worst_error(top_speed),
                      verdict(top_speed.met()));
  }
  md << "\n![Speed during the ramp](ramp_speed.png)\n\n"
        "![Distance during the ramp](ramp_position.png)\n\n";
}

void write_saturation(std::ostream& md, const FidelityResults& results,
                      const FidelityVerdicts& verdicts) {
  md << "### Where torque or traction stops the robot\n\n"
        "The 2 m/s^2 ramp stays below every robot's limits, so each type is also driven with "
        "steeper ramps, as fractions of the acceleration its config predicts. Sent as wheel "
        "speeds (`MODE_WHEEL_SPEEDS`, from the robot's wheel geometry), nothing but physics "
        "limits them; sent as velocity commands, the robot's on-board limit "
        "(`MAX_ACCELERATION`) caps them first. The prediction is worked out from the config "
        "alone (tools/report/predictions.hpp): every wheel pushing with its torque over its "
        "radius, or with its friction times its share of the weight (mu g N/(wheels + "
        "casters)), along the robot's forward axis, less the drag of the omni rollers sliding "
        "across, over the mass (plus the wheels' spin inertia when torque-limited). The "
        "measured saturation is the mean over the wheel-speed ramps at >= 1.3 x the "
        "prediction; below the prediction the robot must follow the command within 5 %.\n\n";
  md << "| robot type | torque-limited | traction-limited | predicted | measured | error | "
        "target | | worst error below saturation | target | | on-board limit | velocity "
        "commands reach |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < results.sweeps.size(); ++i) {
    const SweepResult& s = results.sweeps[i];
    const SweepVerdict& v = verdicts.sweeps[i];
    // What velocity commands reach: the highest rate achieved with them.
    std::optional<double> velocity_plateau;
    for (const auto& p : s.points) {
      if (!p.wheel_speeds) {
        velocity_plateau = std::max(velocity_plateau.value_or(p.truth), p.truth);
      }
    }
    md << fmt::format(
        "| {} | {:.2f} m/s^2 | {:.2f} m/s^2 | {:.2f} m/s^2 ({}) | {:.2f} m/s^2 | {} | ±10 % | {} "
        "| {} | ±5 % | {} | {:.2f} m/s^2 | {} |\n",
        s.settings.robot_type, s.prediction.torque_limited, s.prediction.traction_limited,
        s.prediction.acceleration, s.prediction.limited_by, s.saturation,
        percent(v.saturation.error()), verdict(v.saturation.met()), worst_error(v.below_saturation),
        verdict(v.below_saturation.met()), s.prediction.onboard_limit,
        velocity_plateau ? fmt::format("{:.2f} m/s^2", *velocity_plateau) : std::string("-"));
  }
  md << "\n![Achieved against commanded acceleration](saturation.png)\n\n";
}

void write_figure8(std::ostream& md, const FidelityResults& results, const ExperimentSetup& setup) {
  const Figure8Settings& f = results.figure8.front().settings;
  md << "## 2. Figure-8 (the paper's Figure 8)\n\n";
  md << fmt::format(
      "Robot type `{}` follows a figure-8 {:g} m across at {:g} m/s under the demo team's "
      "published "
      "controller (tools/demo_team: the world model from VISION, `track()` towards "
      "`figure_eight()` with the demo's gains, one radio packet per camera frame), {:g} laps "
      "from rest at the path's start; the errors leave out the first lap. *Tracking error*: "
      "ground truth to where the path says the robot should be at that moment. *Path error*: "
      "distance to the nearest point of the intended curve (the shape, whatever the timing). "
      "Same controller, same seed; only the emulator profiles differ.\n\n",
      f.robot_type, f.size, f.speed, f.laps);
  md << "| run | vision | radio | camera to wheels | tracking RMS / max | path RMS / max "
        "(ground truth) | path RMS / max (VISION) | mean speed |\n"
        "|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : results.figure8) {
    const double latency = profile_value(setup, "vision", r.settings.vision_profile, "LATENCY") +
                           profile_value(setup, "radio", r.settings.radio_profile, "LATENCY");
    md << fmt::format(
        "| {} | {} | {} | {:.0f} ms | {:.1f} / {:.1f} mm | {:.1f} / {:.1f} mm | {:.1f} / {:.1f} "
        "mm | {:.3f} m/s |\n",
        r.settings.label, r.settings.vision_profile, r.settings.radio_profile, latency * 1e3,
        r.tracking.rms * 1e3, r.tracking.max * 1e3, r.contour.rms * 1e3, r.contour.max * 1e3,
        r.vision_contour.rms * 1e3, r.vision_contour.max * 1e3, r.mean_speed);
  }
  if (results.figure8.size() >= 2) {
    const Figure8Result& a = results.figure8[0];
    const Figure8Result& b = results.figure8[1];
    md << fmt::format(
        "\nTarget: show what the emulation costs the controller. With `{}` the tracking error "
        "is {:.1f} mm RMS against {:.1f} mm with `{}` ({:+.1f} mm); the path error {:.1f} mm "
        "against {:.1f} mm ({:+.1f} mm).\n",
        a.settings.label, a.tracking.rms * 1e3, b.tracking.rms * 1e3, b.settings.label,
        (a.tracking.rms - b.tracking.rms) * 1e3, a.contour.rms * 1e3, b.contour.rms * 1e3,
        (a.contour.rms - b.contour.rms) * 1e3);
  }
  md << "\n![Figure-8 paths](figure8_paths.png)\n\n![Figure-8 errors](figure8_error.png)\n\n";
}

void write_chips(std::ostream& md, const BallResult& ball, const BallVerdict& verdict_of) {
  md << fmt::format(
      "Chip kicks at {:.0f} deg: the first flight (launch to first touchdown) against the "
      "ballistic arc with no air drag, d = v^2 sin(2 theta) / g and h = (v sin theta)^2 / "
      "(2 g), g = {:g} m/s^2.\n\n",
      ball.settings.chip_angle * 180 / M_PI, ball.gravity);
  md << "| chip | flight distance | ballistic | error | peak height | ballistic | error | "
        "target | |\n|---|---|---|---|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < ball.chips.size(); ++i) {
    const ChipResult& ch = ball.chips[i];
    const PairVerdict& v = verdict_of.chips[i];
    md << fmt::format(
        "| {:.1f} m/s | {:.3f} m | {:.3f} m | {} | {:.3f} m | {:.3f} m | {} | ±10 % | {} |\n",
        ch.commanded, ch.distance, ch.model.distance, percent(v.first_error), ch.peak,
        ch.model.peak_height, percent(v.second_error), verdict(v.met));
  }
  md << "\n![Chip kicks](ball_chip.png)\n\n";
}

void write_ball(std::ostream& md, const BallResult& ball, const BallVerdict& verdict_of) {
  const physics::BallConfig& c = ball.ball_config;
  md << "## 3. Ball\n\n";
  md << fmt::format(
      "Kicked by the kicker of robot type `{}`, fired through the radio, on a 44 m carpet (a "
      "field file the "
      "report writes) so that no kick reaches a wall; measured in ground truth. The model "
      "from `config/balls/{}.cfg`: sliding at {:g} m/s^2 until the speed is {:g} of the kick "
      "speed, then rolling at {:g} m/s^2 to rest (tools/report/predictions.hpp). Rest = "
      "below 5 mm/s. The fitted decelerations are over the middle 60 % of each phase of the "
      "model.\n\n",
      ball.settings.robot_type, c.name, c.sliding_deceleration, c.slide_to_roll_ratio,
      c.rolling_deceleration);
  md << "| kick | speed 1 step later | roll-out distance | model | error | roll-out time | model "
        "| error | target | | sliding decel. | rolling decel. |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < ball.kicks.size(); ++i) {
    const KickResult& k = ball.kicks[i];
    const PairVerdict& v = verdict_of.kicks[i];
    md << fmt::format(
        "| {:.1f} m/s | {:.3f} m/s | {:.3f} m | {:.3f} m | {} | {:.2f} s | {:.2f} s | {} | ±10 % "
        "| {} | {:.2f} m/s^2 | {:.3f} m/s^2 |\n",
        k.commanded, k.launch_speed, k.distance, k.model.distance, percent(v.first_error), k.time,
        k.model.time, percent(v.second_error), verdict(v.met), k.sliding_deceleration,
        k.rolling_deceleration);
  }
  md << "\n![Ball roll-out](ball_rollout.png)\n\n";
  if (!ball.chips.empty()) write_chips(md, ball, verdict_of);
}

void write_targets(const std::string& dir, const FidelityResults& results,
                   const FidelityVerdicts& verdicts) {
  auto targets = open(dir, "targets_fidelity.md");
  for (const auto& row : verdicts.targets) targets << summary_row(row);
  if (results.figure8.size() >= 2) {
    const Figure8Result& a = results.figure8[0];
    const Figure8Result& b = results.figure8[1];
    targets << fmt::format(
        "| Figure-8 tracking error with the paper's latency beside none (shown, no limit) | "
        "{:.1f} mm RMS ({}) vs {:.1f} mm RMS ({}) | shown | - |\n",
        a.tracking.rms * 1e3, a.settings.label, b.tracking.rms * 1e3, b.settings.label);
  }
}

void write_every_check(std::ostream& md, const FidelityVerdicts& verdicts) {
  md << "### Every check against its tolerance\n\n";
  md << fmt::format("{} of {} checks met.\n\n", verdicts.all.size() - verdicts.missed,
                    verdicts.all.size());
  md << "| check | measured | expected | error | tolerance | |\n|---|---|---|---|---|---|\n";
  for (const auto& c : verdicts.all) {
    md << fmt::format("| {} | {:.4g} | {:.4g} | {} | ±{:.0f} % | {} |\n", c.what, c.measured,
                      c.expected, percent(c.error()), c.tolerance * 100, verdict(c.met()));
  }
  md << "\n";
}

}  // namespace

FidelityVerdicts decide_fidelity(const FidelityResults& results, const Tolerances& tolerances) {
  FidelityVerdicts v;
  std::vector<Check> ramp_checks, sweep_checks, ball_checks;
  for (const auto& r : results.ramps) {
    v.ramps.push_back(decide_ramp(r, tolerances));
    ramp_checks.insert(ramp_checks.end(), v.ramps.back().checks.begin(),
                       v.ramps.back().checks.end());
  }
  for (const auto& s : results.sweeps) {
    v.sweeps.push_back(decide_sweep(s, tolerances));
    sweep_checks.insert(sweep_checks.end(), v.sweeps.back().checks.begin(),
                        v.sweeps.back().checks.end());
  }
  for (const auto& b : results.ball) {
    v.ball.push_back(decide_ball(b, tolerances));
    ball_checks.insert(ball_checks.end(), v.ball.back().checks.begin(), v.ball.back().checks.end());
  }
  v.targets = decide_targets(ramp_checks, sweep_checks, ball_checks);
  v.all = ramp_checks;
  v.all.insert(v.all.end(), sweep_checks.begin(), sweep_checks.end());
  v.all.insert(v.all.end(), ball_checks.begin(), ball_checks.end());
  v.missed = count_missed(v.all);
  return v;
}

void write_fidelity_markdown(const std::string& dir, const FidelityResults& results,
                             const FidelityVerdicts& verdicts, const ExperimentSetup& setup) {
  auto md = open(dir, "fidelity.md");
  if (!results.ramps.empty()) write_acceleration(md, results, verdicts, setup);
  if (!results.sweeps.empty()) write_saturation(md, results, verdicts);
  if (!results.figure8.empty()) write_figure8(md, results, setup);
  for (std::size_t i = 0; i < results.ball.size(); ++i) {
    write_ball(md, results.ball[i], verdicts.ball[i]);
  }
  write_targets(dir, results, verdicts);
  write_every_check(md, verdicts);
}

}  // namespace ubersim::report
