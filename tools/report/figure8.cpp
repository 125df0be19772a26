#include "figure8.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "../demo_team/motion.hpp"
#include "../demo_team/world_model.hpp"

namespace ubersim::report {
namespace {

constexpr double kControlRate = 60;  // Hz, ubersim_demo_team's default --rate
constexpr int kPathSamples = 4000;   // points of the intended curve per lap

double nearest_distance(const std::vector<PathSample>& path, double x, double y) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& p : path) best = std::min(best, std::hypot(p.x - x, p.y - y));
  return best;
}

}  // namespace

Figure8Result run_figure8(const ExperimentSetup& setup, const Figure8Settings& settings) {
  Figure8Result result;
  result.settings = settings;
  // figure_eight()'s own speed law: w = speed / (0.970 a), one lap per 2 pi / w.
  const double a = settings.size / 2;
  result.period = 2 * M_PI * 0.970 * a / settings.speed;
  for (int i = 0; i < kPathSamples; ++i) {
    const double t = result.period * i / kPathSamples;
    const demo::PathPoint p = demo::figure_eight(t, 0, 0, settings.size, settings.speed);
    result.path.push_back({t, p.x, p.y});
  }

  RigOptions options;
  options.name = "figure8_" + settings.label;
  options.scenario = setup.centre_scenario(settings.robot_type);
  options.vision_profile = settings.vision_profile;
  options.radio_profile = settings.radio_profile;
  options.vision_seed = options.radio_seed = settings.seed;
  SimRig rig(setup.paths(), options);

  std::vector<RobotSample> truth;
  std::vector<vision_frame_t> new_frames;
  rig.on_state([&](const sim_state_t& s) {
    RobotSample r;
    if (find_robot(s, kRobot, r)) truth.push_back(r);
  });
  rig.on_frame([&](const vision_frame_t& f) { new_frames.push_back(f); });

  // Start at rest where the path starts, facing along it.
  const demo::PathPoint start = demo::figure_eight(0, 0, 0, settings.size, settings.speed);
  rig.place(place_robot(kRobot, start.x, start.y, std::atan2(start.vy, start.vx)));
  rig.step(1);
  new_frames.clear();
  truth.clear();
  const double t0 = rig.time();

  // The demo team's loop (tools/demo_team/main.cpp, --mode figure8): every
  // frame updates the world model; at most --rate packets per second of
  // capture time; the path is followed in capture time.
  demo::WorldModel world(true);
  demo::MotionLimits limits;  // the demo team's defaults
  double last_sent = -1e9;
  const double duration = settings.laps * result.period;
  while (rig.time() - t0 < duration) {
    rig.step(1);
    std::vector<vision_frame_t> frames;
    frames.swap(new_frames);
    for (const auto& frame : frames) {
      if (frame.t_capture < t0) continue;
      world.update(frame);
      if (world.now() - last_sent < 1.0 / kControlRate - 1e-9) continue;
      const auto own = world.own().find(kRobot);
      if (own == world.own().end()) continue;
      last_sent = world.now();
      const demo::PathPoint p =
          demo::figure_eight(world.now() - t0, 0, 0, settings.size, settings.speed);
      radio_packet_t packet{};
      packet.t_sent = world.now();
      packet.commands.push_back(
          demo::track(kRobot, own->second, p.x, p.y, p.vx, p.vy, std::atan2(p.vy, p.vx), limits));
      rig.send(packet);
      ++result.packets;
    }
    for (const auto& frame : frames) {
      RobotDetection d;
      if (frame.t_capture >= t0 && find_detection(frame, kRobot, d)) {
        result.vision.push_back({d.t - t0, d.x, d.y});
      }
    }
  }
  const std::string problems = rig.stop();
  if (!problems.empty()) throw std::runtime_error(problems);

  std::vector<double> tracking, contour, vision_contour;
  double distance = 0, measured_time = 0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const RobotSample& r = truth[i];
    const double t = r.t - t0;
    const demo::PathPoint p = demo::figure_eight(t, 0, 0, settings.size, settings.speed);
    result.truth.push_back({t, r.x, r.y});
    result.reference.push_back({t, p.x, p.y});
    if (t < result.period) continue;
    tracking.push_back(std::hypot(r.x - p.x, r.y - p.y));
    contour.push_back(nearest_distance(result.path, r.x, r.y));
    if (i > 0) {
      distance += std::hypot(r.x - truth[i - 1].x, r.y - truth[i - 1].y);
      measured_time += r.t - truth[i - 1].t;
    }
  }
  for (const auto& v : result.vision) {
    if (v.t >= result.period) vision_contour.push_back(nearest_distance(result.path, v.x, v.y));
  }
  result.tracking = summarise(tracking);
  result.contour = summarise(contour);
  result.vision_contour = summarise(vision_contour);
  result.mean_speed = measured_time > 0 ? distance / measured_time : 0;
  return result;
}

}  // namespace ubersim::report
