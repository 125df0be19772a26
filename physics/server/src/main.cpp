// ubersim_physics: the physics server (see physics_shell.hpp and
// docs/physics.md). Exits 0 on SIGINT/SIGTERM or after --duration.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>

#include "ubersim/cli.hpp"
#include "ubersim/config.hpp"
#include "ubersim/logging.hpp"
#include "ubersim/physics/physics_shell.hpp"
#include "ubersim/physics/single_instance.hpp"
#include "ubersim/process_host.hpp"
#include "ubersim/process_main.hpp"

namespace {

int run(int argc, char** argv) {
  CLI::App app{"ubersim physics server: owns the simulated world (ODE) and steps it"};
  ubersim::CommonOptions common;
  ubersim::add_common_options(app, common);
  std::string scenario = "division_b_6v6";
  std::string physics_config = "default";
  double speed = 1.0;
  bool lockstep = false;
  bool paused = false;
  std::uint64_t seed = 0;
  double duration = 0;
  app.add_option("--scenario", scenario, "scenario config: field, ball and robots")
      ->capture_default_str();
  std::string field;
  app.add_option("--field", field,
                 "field config (config/fields/<name>.cfg or a path) instead of the scenario's; "
                 "robots and ball keep their places scaled to its size");
  app.add_option("--physics-config", physics_config, "config/physics/<name>.cfg: step, solver...")
      ->capture_default_str();
  app.add_option("--speed", speed, "times real time (0.5, 4 ...); 0 = as fast as possible")
      ->capture_default_str()
      ->check(ubersim::at_least(0));
  app.add_flag("--lockstep", lockstep, "advance only on STEP requests (SIM_CONTROL)");
  bool sync = false;
  app.add_flag("--sync", sync,
               "sync mode: as fast as possible, but never past the horizon the radio emulator "
               "announces (--sync there too; docs/sync.md)");
  bool sync_referee = false;
  app.add_flag("--sync-referee", sync_referee,
               "with --sync: also wait for the automatic referee's horizon (ubersim_referee auto "
               "--sync), so its placements apply at a fixed step (docs/autoref.md)");
  // Ground truth on demand is the default (docs/sync.md, "Ground truth on
  // demand"): every reader of SIM_STATE in this tree says what it needs.
  bool truth_every_step = false;
  app.add_flag("--truth-every-step", truth_every_step,
               "publish SIM_STATE after every step, whatever else is asked for; "
               "STATE_PUBLISH_RATE then changes nothing (it thins only what goes out while "
               "nobody asks). Default: the states consumers ask for on SIM_TRUTH_DEMAND "
               "(docs/sync.md)");
  bool truth_on_demand = false;
  app.add_flag("--truth-on-demand", truth_on_demand, "the default; kept for older scripts")
      ->excludes("--truth-every-step");
  app.add_flag("--paused", paused, "start paused (RESUME or STEP to advance)");
  bool wait_for_vision = false;
  app.add_flag("--wait-for-vision", wait_for_vision,
               "hold at sim time 0 until a vision emulator listens (SIM_VISION_SCHEDULE), so it "
               "sees the run from its start (sync mode always does; docs/vision.md)");
  app.add_option("--seed", seed, "seed of the solver's randomness")
      ->check(ubersim::whole_number())
      ->capture_default_str();
  app.add_option("--duration", duration, "exit after this many seconds of sim time (0 = never)")
      ->capture_default_str()
      ->check(ubersim::at_least(0));
  bool check_bus = false;
  app.add_flag("--check-bus", check_bus,
               "only check that no other physics runs on this bus (LCM port and channel "
               "prefix): exit 0 if none does, else 1 with the line naming it");
  if (const auto stop = ubersim::parse_command_line(app, argc, argv)) return *stop;

  ubersim::setup_logging("physics", common.verbosity());
  // Before anything else: a second physics on this bus stops here, naming the
  // first, before it loads a world or publishes (docs/physics.md, "One physics per bus").
  if (check_bus) {
    ubersim::physics::BusClaim::check(common.lcm_url, common.channel_prefix);
    return 0;
  }
  const auto claim = ubersim::physics::BusClaim::claim(common.lcm_url, common.channel_prefix);
  ubersim::physics::WorldSetup setup =
      ubersim::physics::load_world_setup(common.config_root(), scenario, physics_config);
  if (!field.empty()) {
    ubersim::physics::put_on_field(setup, ubersim::load_field_config(common.config_root(), field));
  }
  setup.seed = seed;
  ubersim::physics::ShellOptions options;
  options.scenario = scenario;
  options.speed = lockstep ? -1.0 : speed;
  options.paused = paused;
  options.duration = duration;
  options.sync = sync || sync_referee;
  options.sync_referee = sync_referee;
  options.truth_on_demand = !truth_every_step;
  options.wait_for_vision = wait_for_vision;
  ubersim::ProcessHost host(common, "physics");
  ubersim::physics::PhysicsShell shell(std::move(setup), host, options);
  return shell.run();
}

}  // namespace

int main(int argc, char** argv) {
  return ubersim::run_main("ubersim_physics", [&] { return run(argc, argv); });
}
