// ubersim_physics_bench: how fast the physics runs, as simulated seconds per
// wall second, for 2 x 11 (Division A), 2 x 6 (Division B) and 2 x 5 (2002
// field) robots with each drive model; beside each, in the same run, the same
// scene stepped by bare ODE (no framework, no messages), so the figure reads
// as ubersim's overhead over bare ODE. The ubersim figure is the full server
// (PhysicsShell on its ProcessHost) running as fast as possible with SIM_STATE published every
// step (memq:// by default, or any LCM URL) and commands arriving on
// SIM_COMMANDS at 60 Hz.
//
//   --pacing S   instead: run in real time for S s of sim time and print the drift.

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <ubersim/sim_commands_t.hpp>

#include "bare_ode_scene.hpp"
#include "bench_support.hpp"
#include "ubersim/cli.hpp"
#include "ubersim/config_paths.hpp"
#include "ubersim/logging.hpp"
#include "ubersim/physics/physics_shell.hpp"
#include "ubersim/process_host.hpp"
#include "ubersim/process_main.hpp"
#include "ubersim/topics.hpp"

namespace {

using ubersim::physics::bench::load_average;

using namespace ubersim;
using namespace ubersim::physics;
using Clock = std::chrono::steady_clock;

constexpr int kStepsPerCommand = 4;  // 60 Hz radio at 240 Hz physics

// The same motion for every run: each robot weaves and turns on its own phase.
void motion(std::size_t robot, double t, double out[3]) {
  const double phase = 0.7 * static_cast<double>(robot);
  out[0] = 1.5 * std::cos(0.8 * t + phase);
  out[1] = 1.5 * std::sin(1.1 * t + 2 * phase);
  out[2] = 2.0 * std::sin(0.5 * t + phase);
}

WorldSetup setup_for(const std::string& config_dir, const std::string& scenario, DriveModel model) {
  WorldSetup setup = load_world_setup(config_dir, scenario, "default");
  auto base = setup.robot_types;
  setup.robot_types = [base, model](const std::string& name) {
    auto type = std::make_shared<RobotTypeConfig>(*base(name));
    type->model = model;
    return std::shared_ptr<const RobotTypeConfig>(type);
  };
  return setup;
}

// Feeds SIM_COMMANDS from inside the bus, every kStepsPerCommand states,
// without decoding the states (a consumer's cost is not the server's).
struct CommandFeeder {
  MessageBus* bus = nullptr;
  std::string commands_channel;
  std::vector<std::pair<Team, int>> robots;
  std::int64_t states = 0;
  double dt = 0;

  void on_state() {
    CommandFeeder* self = this;
    if (self->states++ % kStepsPerCommand != 0) return;
    const double t = static_cast<double>(self->states - 1) * self->dt;
    for (Team team : kTeams) {
      sim_commands_t packet{};
      packet.team = static_cast<int8_t>(team);
      packet.t_received = t;
      packet.t_apply = t;
      for (std::size_t i = 0; i < self->robots.size(); ++i) {
        if (self->robots[i].first != team) continue;
        double v[3];
        motion(i, t, v);
        robot_command_t c{};
        c.robot_id = self->robots[i].second;
        c.mode = robot_command_t::MODE_LOCAL_VELOCITY;
        c.vx = v[0];
        c.vy = v[1];
        c.omega = v[2];
        packet.commands.push_back(c);
      }
      packet.num_commands = static_cast<int32_t>(packet.commands.size());
      self->bus->publish(self->commands_channel, packet);
    }
  }
};

double run_server(const WorldSetup& setup, const std::string& url, double sim_seconds, double speed,
                  ServerStats* stats_out = nullptr) {
  ProcessHost host(with_receive_buffer(url), ChannelNames(), "physics");
  ShellOptions options;
  options.scenario = "benchmark";
  options.speed = speed;
  options.duration = sim_seconds;
  PhysicsShell shell(setup, host, options);
  CommandFeeder feeder;
  feeder.bus = &host.bus();
  feeder.commands_channel = channel_name(host.channels(), topics::kSimCommands);
  feeder.dt = shell.world().dt();
  for (const auto& r : shell.world().robots()) feeder.robots.emplace_back(r->team(), r->id());
  host.bus().subscribe_raw(
      channel_name(host.channels(), topics::kSimState),
      [&feeder](const std::string&, const void*, std::size_t, std::int64_t) { feeder.on_state(); });
  shell.run();
  // The host stops a run on Ctrl-C; the bench stops with it rather than go on to the next run.
  if (host.shutdown().requested()) throw std::runtime_error("stopped (Ctrl-C)");
  if (stats_out != nullptr) *stats_out = shell.stats();
  return sim_seconds / shell.stats().wall_seconds;
}

double run_world_only(const WorldSetup& setup, double sim_seconds) {
  World world(setup);
  std::vector<std::pair<Team, int>> robots;
  for (const auto& r : world.robots()) robots.emplace_back(r->team(), r->id());
  const auto start = Clock::now();
  while (world.time() < sim_seconds - world.dt() / 2) {
    if (world.step_index() % kStepsPerCommand == 0) {
      for (std::size_t i = 0; i < robots.size(); ++i) {
        double v[3];
        motion(i, world.time(), v);
        robot_command_t c{};
        c.robot_id = robots[i].second;
        c.vx = v[0];
        c.vy = v[1];
        c.omega = v[2];
        world.command(robots[i].first, robots[i].second, c);
      }
    }
    world.step();
  }
  return sim_seconds / std::chrono::duration<double>(Clock::now() - start).count();
}

double run_bare(const WorldSetup& setup, DriveModel model, double sim_seconds) {
  bench::BareOdeScene scene(setup, model);
  const double dt = setup.physics.dt();
  const auto steps = static_cast<std::int64_t>(std::lround(sim_seconds / dt));
  const auto start = Clock::now();
  for (std::int64_t s = 0; s < steps; ++s) {
    if (s % kStepsPerCommand == 0) {
      for (std::size_t i = 0; i < scene.robot_count(); ++i) {
        double v[3];
        motion(i, static_cast<double>(s) * dt, v);
        scene.command(i, v[0], v[1], v[2]);
      }
    }
    scene.step();
  }
  return sim_seconds / std::chrono::duration<double>(Clock::now() - start).count();
}

struct BenchOptions {
  std::string url = "memq://";
  std::string config_dir = default_config_dir().string();
  double seconds = 0;
  int repeat = 3;
  double pacing = 0;
  std::vector<std::string> scenarios = {"division_a_11v11", "division_b_6v6", "field2002_5v5"};
  std::vector<std::string> models = {"jointed", "planar"};
  std::string only;
  double state_rate = -1;  // Hz of sim time; < 0: the physics config's STATE_PUBLISH_RATE
};

int run_benchmark(const BenchOptions& options) {
  const std::string& url = options.url;
  const std::string& config_dir = options.config_dir;
  const double seconds = options.seconds;
  const int repeat = options.repeat;
  const double pacing = options.pacing;
  const std::vector<std::string>& scenarios = options.scenarios;
  const std::vector<std::string>& models = options.models;
  const std::string& only = options.only;
  setup_logging("bench", -2);

  if (pacing > 0) {
    ServerStats stats;
    run_server(setup_for(config_dir, scenarios.front(), DriveModel::Jointed), url, pacing, 1.0,
               &stats);
    std::printf(
        "real time, %s, %.0f s of sim time: wall %.4f s, sim time %+.2f ms from the wall "
        "clock at the end, %lld schedule restarts (machine load %s)\n",
        scenarios.front().c_str(), pacing, stats.wall_seconds, stats.drift * 1e3,
        static_cast<long long>(stats.schedule_restarts), load_average().c_str());
    return 0;
  }

  const PhysicsConfig default_physics = load_physics_config(config_dir, "default");
  const double state_rate =
      options.state_rate >= 0 ? options.state_rate : default_physics.state_publish_rate;
  const std::string state_rate_text =
      state_rate > 0 ? "at " + std::to_string(static_cast<int>(state_rate)) + " Hz of sim time"
                     : std::string("every step");
  std::printf(
      "ubersim physics benchmark: 240 Hz, QuickStep %d iterations, as fast as possible,\n"
      "SIM_STATE published %s on %s, commands at 60 Hz; best of %d runs.\n"
      "Load average at start: %s (the machine is shared: figures vary with load).\n\n",
      default_physics.solver_iterations, state_rate_text.c_str(), url.c_str(), repeat,
      load_average().c_str());
  std::printf("%-18s %-6s %-8s %12s %12s %12s %10s\n", "scenario", "robots", "model", "server [x]",
              "world [x]", "bare ODE [x]", "overhead");
  for (const std::string& scenario : scenarios) {
    for (const std::string& model_name : models) {
      const DriveModel model = model_name == "planar" ? DriveModel::Planar : DriveModel::Jointed;
      WorldSetup setup = setup_for(config_dir, scenario, model);
      if (options.state_rate >= 0) setup.physics.state_publish_rate = options.state_rate;
      const double sim = seconds > 0 ? seconds : (model == DriveModel::Jointed ? 20.0 : 60.0);
      double server = 0, world = 0, bare = 0;
      for (int i = 0; i < repeat; ++i) {
        if (only.empty() || only == "bare") bare = std::max(bare, run_bare(setup, model, sim));
        if (only.empty() || only == "world") world = std::max(world, run_world_only(setup, sim));
        if (only.empty() || only == "server") {
          server = std::max(server, run_server(setup, url, sim, 0.0));
        }
      }
      std::printf("%-18s %2zux%-3zu %-8s %12.1f %12.1f %12.1f %+9.1f%%\n", scenario.c_str(),
                  setup.robots.size() / 2, setup.robots.size() - setup.robots.size() / 2,
                  model == DriveModel::Jointed ? "jointed" : "planar", server, world, bare,
                  (bare / server - 1) * 100);
      std::fflush(stdout);
    }
  }
  std::printf(
      "\nserver: the ubersim_physics server loop with messages; world: the World alone;\n"
      "overhead: server time over bare ODE time, minus 1.\n");
  return 0;
}

}  // namespace

int run(int argc, char** argv) {
  CLI::App app{"ubersim physics benchmark: simulated seconds per wall second"};
  BenchOptions o;
  app.add_option("-l,--lcm-url", o.url, "where SIM_STATE goes (memq:// = in-process)")
      ->capture_default_str();
  app.add_option("--config-dir", o.config_dir, "config folder")->capture_default_str();
  app.add_option("--seconds", o.seconds, "sim seconds per run (0: 20 jointed, 60 planar)");
  app.add_option("--repeat", o.repeat, "runs of each, the fastest counts")->capture_default_str();
  app.add_option("--scenarios", o.scenarios, "scenarios to run")->capture_default_str();
  app.add_option("--pacing", o.pacing, "only check real-time pacing for this many sim seconds");
  app.add_option("--models", o.models, "drive models to run")->capture_default_str();
  app.add_option("--state-rate", o.state_rate,
                 "SIM_STATE rate (Hz of sim time, 0 = every step; default: the physics config's)");
  app.add_option("--only", o.only, "run just one variant: server, world or bare (for profiling)");
  if (const auto stop = ubersim::parse_command_line(app, argc, argv)) return *stop;
  try {
    return run_benchmark(o);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ubersim_physics_bench: %s\n", e.what());
    return 1;
  } catch (...) {
    return 1;
  }
}

int main(int argc, char** argv) {
  return ubersim::run_main("ubersim_physics_bench", [&] { return run(argc, argv); });
}
