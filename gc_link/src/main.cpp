// ubersim_gc_link: the official ssl-game-controller referees a sync-mode game
// through its CI port, with simulation time as its clock (docs/official_gc.md).
// Exit status: 0 game over (or stopped by a signal), 1 the GC failed, 2 bad usage or a config
// error.
#include <CLI/CLI.hpp>
#include <iostream>

#include "gc_link_shell.hpp"
#include "ubersim/cli.hpp"
#include "ubersim/field_side.hpp"
#include "ubersim/logging.hpp"
#include "ubersim/process_main.hpp"

namespace {

using namespace ubersim;
using namespace ubersim::gc_link;

int parse_and_run(int argc, char** argv) {
  GcLinkOptions o;
  CLI::App app{
      "ubersim_gc_link: the official ssl-game-controller referees a sync-mode game through its "
      "CI port, with simulation time as its clock; REFEREE in sim time, physics waits for it "
      "(start physics with --sync-referee)"};
  add_common_options(app, o.common);
  auto* binary = app.add_option("--game-controller", o.game_controller,
                                "start this ssl-game-controller binary (CI mode, a free port)");
  auto* address = app.add_option("--gc-address", o.gc_address,
                                 "or use a game controller already running in CI mode (HOST:PORT)");
  binary->excludes(address);
  app.add_option("--gc-dir", o.gc_dir, "folder of the started game controller (config, log)")
      ->capture_default_str();
  app.add_option("--game", o.game,
                 "game config (config/referee/<name>.cfg): keepers, first "
                 "kick-off, the rules of ubersim's detectors")
      ->capture_default_str();
  app.add_option("--game-length", o.game_length, "s of sim time, both halves (GC half duration)")
      ->check(greater_than(0));
  app.add_option("--half-time", o.half_time, "s of sim time of the half-time break")
      ->check(at_least(0))
      ->capture_default_str();
  app.add_option("--tick-period", o.tick_period, "s of sim time between game controller ticks")
      ->check(in_range(0.001, 1))
      ->capture_default_str();
  app.add_option("--timeout", o.timeout_s, "s to wait for physics, the GC's start, each answer")
      ->check(greater_than(0))
      ->capture_default_str();
  app.add_option("--yellow-name", o.yellow_name, "team name")->capture_default_str();
  app.add_option("--blue-name", o.blue_name, "team name")->capture_default_str();
  app.add_option("--yellow-defends", o.yellow_defends, "side yellow defends")
      ->check(CLI::IsMember(kDefendedSides))
      ->capture_default_str();
  app.add_option("--events", o.events_file, "write the event log (JSON lines) here");
  app.add_flag("--keep-running", o.keep_running, "do not exit when the game is over");
  if (const auto stop = parse_command_line(app, argc, argv)) return *stop;
  if (o.game_controller.empty() && o.gc_address.empty()) {
    std::cerr << "ubersim_gc_link: give --game-controller PATH or --gc-address HOST:PORT\n";
    return 2;
  }
  setup_logging("gc_link", o.common.verbosity());
  return run_gc_link(o);
}

}  // namespace

int main(int argc, char** argv) {
  return ubersim::run_main("ubersim_gc_link", [&] { return parse_and_run(argc, argv); });
}
