// ubersim_vision_benchmark: what the vision emulator costs and how late its
// frames really are.
//
// 1. CPU time per camera frame with 22 robots and a ball (in process, the
//    emulator core fed 240 Hz states), against a baseline measured in the same
//    run: decoding one such SIM_STATE, which the process must do 240 times a
//    second anyway.
// 2. Real-time mode: the real ubersim_vision process, fed SIM_STATE at
//    wall-clock pace (240 Hz) over LCM; a VISION listener measures, per frame,
//    the wall time from the publication of the captured state to the frame's
//    arrival, against the configured latency.
//
// Run it on a port of its own, e.g.
//   tests/run_isolated.sh bench build/bin/ubersim_vision_benchmark
#include <signal.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <numeric>
#include <thread>
#include <ubersim/sim_control_t.hpp>
#include <ubersim/team_t.hpp>
#include <vector>

#include "ubersim/child_process.hpp"
#include "ubersim/cli.hpp"
#include "ubersim/config_paths.hpp"
#include "ubersim/field_config.hpp"
#include "ubersim/message_bus.hpp"
#include "ubersim/topics.hpp"
#include "ubersim/vision/vision_emulator.hpp"

namespace {

using ubersim::sim_state_t;
using ubersim::vision::VisionEmulator;
using WallClock = std::chrono::steady_clock;

constexpr double kDt = 1.0 / 240;
constexpr int kRobotsPerTeam = 11;

double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// 22 robots moving over a Division A field; yellow 0 dribbles the ball, so
// the occlusion test has work to do every frame.
sim_state_t game_state(std::int64_t step) {
  const double t = static_cast<double>(step) * kDt;
  sim_state_t s{};
  s.sim_time = t;
  s.step = step;
  s.dt = kDt;
  s.speed_factor = 1;
  for (int team = 0; team < 2; ++team) {
    for (int i = 0; i < kRobotsPerTeam; ++i) {
      ubersim::robot_state_t r{};
      r.team = static_cast<std::int8_t>(team);
      r.robot_id = i;
      r.robot_type = "omni4_ssl";
      const double phase = i * 0.57 + team * 1.3;
      r.x = (team == 0 ? -3.0 : 3.0) + 2.2 * std::cos(0.4 * t + phase);
      r.y = -3.5 + 0.7 * i + 0.3 * std::sin(0.9 * t + phase);
      r.orientation = std::remainder(0.7 * t + phase, 2 * M_PI);
      r.body.position[0] = r.x;
      r.body.position[1] = r.y;
      r.body.orientation[0] = 1;
      r.num_wheels = 4;
      r.wheel_speeds.assign(4, 10.0);
      r.last_command_time = t;
      s.robots.push_back(r);
    }
  }
  s.num_robots = static_cast<std::int32_t>(s.robots.size());
  const auto& dribbler = s.robots[0];
  const double reach = 0.075 + 0.0215;
  s.ball_present = true;
  s.ball.position[0] = dribbler.x + reach * std::cos(dribbler.orientation);
  s.ball.position[1] = dribbler.y + reach * std::sin(dribbler.orientation);
  s.ball.position[2] = 0.0215;
  s.ball.orientation[0] = 1;
  return s;
}

struct CpuFigures {
  double per_frame_us = 0;
  double per_state_us = 0;
  std::uint64_t frames = 0;
};

CpuFigures measure_cpu(const ubersim::vision::VisionProfile& profile, const std::string& config_dir,
                       double sim_seconds) {
  VisionEmulator emulator(profile, ubersim::vision::RobotSizes::from_config_dir(config_dir));
  const auto steps = static_cast<std::int64_t>(sim_seconds / kDt);
  // Built beforehand so that only the emulator's work is timed.
  std::vector<sim_state_t> states;
  states.reserve(2400);
  for (std::int64_t step = 0; step < 2400; ++step) states.push_back(game_state(step));
  emulator.on_sim_state(states[0]);  // loads the robot type once, outside the timing
  std::size_t published = 0;
  const double start = thread_cpu_seconds();
  for (std::int64_t step = 1; step < steps; ++step) {
    sim_state_t& s = states[static_cast<std::size_t>(step % 2400)];
    s.step = step;
    s.sim_time = static_cast<double>(step) * kDt;
    published += emulator.on_sim_state(s).frames.size();
  }
  const double cpu = thread_cpu_seconds() - start;
  CpuFigures figures;
  figures.frames = emulator.stats().frames_captured;
  figures.per_frame_us =
      1e6 * cpu / static_cast<double>(std::max<std::uint64_t>(1, figures.frames));
  figures.per_state_us = 1e6 * cpu / static_cast<double>(steps - 1);
  if (published == 0) std::printf("warning: no frame published\n");
  return figures;
}

double measure_decode_us() {
  const sim_state_t state = game_state(1);
  std::vector<char> bytes(static_cast<std::size_t>(state.getEncodedSize()));
  state.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  const int rounds = 20000;
  sim_state_t decoded;
  const double start = thread_cpu_seconds();
  // What a process pays: the bounds check, then the decode.
  for (int i = 0; i < rounds; ++i) ubersim::decode_bounded(bytes.data(), bytes.size(), decoded);
  return 1e6 * (thread_cpu_seconds() - start) / rounds;
}

// --- real-time mode -----------------------------------------------------------

std::string vision_program() {
  const auto own = std::filesystem::read_symlink("/proc/self/exe").parent_path() / "ubersim_vision";
  return std::filesystem::exists(own) ? own.string() : std::string(UBERSIM_VISION_PROGRAM);
}

struct Percentiles {
  double mean = 0, p50 = 0, p95 = 0, p99 = 0, max = 0;
};
Percentiles percentiles(std::vector<double> v) {
  Percentiles p;
  if (v.empty()) return p;
  std::sort(v.begin(), v.end());
  auto at = [&](double q) {
    return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))];
  };
  p.mean = std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
  p.p50 = at(0.5);
  p.p95 = at(0.95);
  p.p99 = at(0.99);
  p.max = v.back();
  return p;
}

void measure_realtime(const std::string& profile_name,
                      const ubersim::vision::VisionProfile& profile, const std::string& url,
                      const std::string& config_dir, double seconds) {
  ubersim::ChannelNames channels;
  ubersim::MessageBus listener(ubersim::with_receive_buffer(url));
  ubersim::MessageBus publisher(url);
  const auto steps = static_cast<std::int64_t>(seconds / kDt);
  std::vector<WallClock::time_point> sent(static_cast<std::size_t>(steps));
  std::atomic<std::int64_t> last_sent{-1};  // sent[] is written up to here
  std::map<int, double> latency_of;         // per camera (s)
  for (const auto& c : profile.cameras) latency_of[c.id] = c.latency;

  std::vector<double> delays, excess;
  bool ready = false;
  ubersim::subscribe(
      listener, channels, ubersim::topics::kSimControl,
      std::function<void(const ubersim::sim_control_t&)>([&](const ubersim::sim_control_t& c) {
        if (c.action == ubersim::sim_control_t::REQUEST_GEOMETRY) ready = true;
      }));
  ubersim::subscribe(
      listener, channels, ubersim::topics::kVision,
      std::function<void(const ubersim::vision_frame_t&)>([&](const ubersim::vision_frame_t& f) {
        const auto arrival = WallClock::now();
        const auto step = static_cast<std::int64_t>(std::llround(f.t_capture / kDt));
        if (step < 0 || step > last_sent.load(std::memory_order_acquire)) return;
        const double delay =
            std::chrono::duration<double>(arrival - sent[static_cast<std::size_t>(step)]).count();
        delays.push_back(delay);
        excess.push_back(delay - latency_of[f.camera_id]);
      }),
      10000);

  std::unique_ptr<ubersim::ChildProcess> child;
  try {
    child = std::make_unique<ubersim::ChildProcess>(
        std::vector<std::string>{vision_program(), "--profile", profile_name, "--config-dir",
                                 config_dir, "-l", url},
        "");
  } catch (const std::exception& error) {
    std::printf("  cannot start %s: %s\n", vision_program().c_str(), error.what());
    return;
  }
  const auto give_up = WallClock::now() + std::chrono::seconds(15);
  while (!ready && WallClock::now() < give_up) listener.wait_and_handle(50);
  if (!ready) {
    std::printf("  ubersim_vision did not come up\n");
    return;
  }
  ubersim::publish(publisher, channels, ubersim::topics::kSimGeometry,
                   ubersim::load_field_config(config_dir, "division_a").to_message(0.0215));

  std::atomic<bool> done{false};
  std::thread driver([&] {
    const auto start = WallClock::now();
    for (std::int64_t step = 0; step < steps; ++step) {
      const auto due = start + std::chrono::duration_cast<WallClock::duration>(
                                   std::chrono::duration<double>(static_cast<double>(step) * kDt));
      std::this_thread::sleep_until(due);
      const sim_state_t state = game_state(step);
      sent[static_cast<std::size_t>(step)] = WallClock::now();
      last_sent.store(step, std::memory_order_release);
      ubersim::publish(publisher, channels, ubersim::topics::kSimState, state);
    }
    done = true;
  });
  while (!done) listener.wait_and_handle(20);
  driver.join();
  const auto drain = WallClock::now() + std::chrono::milliseconds(300);
  while (WallClock::now() < drain) listener.wait_and_handle(20);
  child->stop(2);

  const auto d = percentiles(delays), e = percentiles(excess);
  double configured = 0;
  for (const auto& [id, latency] : latency_of) configured = std::max(configured, latency);
  std::printf("  %zu frames over %.0f s wall; configured latency %.1f ms (jitter %.1f ms)\n",
              delays.size(), seconds, 1e3 * configured, 1e3 * profile.latency_jitter);
  std::printf("  observed delay   ms: mean %6.2f  p50 %6.2f  p95 %6.2f  p99 %6.2f  max %6.2f\n",
              1e3 * d.mean, 1e3 * d.p50, 1e3 * d.p95, 1e3 * d.p99, 1e3 * d.max);
  std::printf("  minus configured ms: mean %6.2f  p50 %6.2f  p95 %6.2f  p99 %6.2f  max %6.2f\n",
              1e3 * e.mean, 1e3 * e.p50, 1e3 * e.p95, 1e3 * e.p99, 1e3 * e.max);
  std::printf(
      "  (a frame leaves at the first 240 Hz step at or after capture + latency: "
      "+%.2f ms on average from the step alone)\n",
      1e3 * kDt / 2);
}

int run(int argc, char** argv) {
  CLI::App app{"ubersim vision emulator benchmark: CPU per frame, real-time end-to-end delay"};
  std::vector<std::string> profiles{"cmdragons02", "modern"};
  double cpu_sim_seconds = 120;
  double realtime_seconds = 10;
  std::string url = ubersim::default_lcm_url();
  std::string config_dir = ubersim::default_config_dir().string();
  app.add_option("--profile", profiles, "profiles to measure")->capture_default_str();
  app.add_option("--cpu-seconds", cpu_sim_seconds, "sim seconds fed for the CPU figures")
      ->capture_default_str();
  app.add_option("--realtime-seconds", realtime_seconds, "wall seconds of real-time mode, 0 = skip")
      ->capture_default_str();
  app.add_option("-l,--lcm-url", url, "LCM URL for real-time mode")->capture_default_str();
  app.add_option("--config-dir", config_dir, "config folder")->capture_default_str();
  if (const auto stop = ubersim::parse_command_line(app, argc, argv)) return *stop;
  spdlog::set_level(spdlog::level::err);

  const double decode_us = measure_decode_us();
  std::printf("baseline: decoding one SIM_STATE with %d robots: %.2f us CPU\n\n",
              2 * kRobotsPerTeam, decode_us);
  for (const std::string& name : profiles) {
    const auto profile = ubersim::vision::load_vision_profile(config_dir, name);
    const CpuFigures cpu = measure_cpu(profile, config_dir, cpu_sim_seconds);
    std::printf("profile %s (%zu camera(s)), %d robots + ball, 240 Hz states:\n", name.c_str(),
                profile.cameras.size(), 2 * kRobotsPerTeam);
    std::printf(
        "  CPU per camera frame %.2f us (%.1f x a SIM_STATE decode), per state %.2f us; "
        "%llu frames\n",
        cpu.per_frame_us, cpu.per_frame_us / decode_us, cpu.per_state_us,
        static_cast<unsigned long long>(cpu.frames));
    std::printf("  share of one core at 240 Hz, decode included: %.2f %%\n",
                100 * 240 * (cpu.per_state_us + decode_us) * 1e-6);
    if (realtime_seconds > 0) measure_realtime(name, profile, url, config_dir, realtime_seconds);
    std::printf("\n");
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "ubersim_vision_benchmark: %s\n", error.what());
  } catch (...) {
    std::fprintf(stderr, "ubersim_vision_benchmark: unknown error\n");
  }
  return 1;
}
