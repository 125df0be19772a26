// ubersim_radio: the radio emulator process. Listens where each team's real
// radio server would (RADIO_YELLOW / RADIO_BLUE) and forwards what an
// emulated radio link lets through to physics on SIM_COMMANDS; returns the
// robots' feedback on RADIO_FEEDBACK_<TEAM>. See docs/radio.md; its shell
// (RadioShell, around the RadioEmulator core) is radio_shell.cpp.
#include <CLI/CLI.hpp>

#include "radio_shell.hpp"
#include "ubersim/cli.hpp"
#include "ubersim/logging.hpp"
#include "ubersim/process_main.hpp"

namespace {

int parse_and_run(int argc, char** argv) {
  ubersim::radio::RadioOptions options;
  CLI::App app{"ubersim radio emulator: each team's radio link (rate limit, latency, loss)"};
  ubersim::add_common_options(app, options.common);
  app.add_option("--profile", options.profile,
                 "radio profile for both teams: config/radio/NAME.cfg or a path")
      ->capture_default_str();
  app.add_option("--yellow-profile", options.yellow_profile, "profile for the yellow team only");
  app.add_option("--blue-profile", options.blue_profile, "profile for the blue team only");
  app.add_option("--seed", options.seed, "seed of every random draw (default: the profiles' SEED)")
      ->check(ubersim::whole_number());
  app.add_flag("--sync", options.sync,
               "sync mode: registered clients answer every frame; tell physics how far it may "
               "step (SIM_SYNC_HORIZON, docs/sync.md)");
  app.add_option("--sync-timeout", options.sync_options.client_timeout,
                 "s of wall time a sync client may take to answer a frame; then it is dropped")
      ->capture_default_str()
      ->check(ubersim::greater_than(0));
  app.add_flag("--sync-strict", options.sync_options.strict,
               "a sync client missing the timeout fails the run (exit 1)");
  app.add_option("--sync-clients", options.sync_options.expected_clients,
                 "physics holds at the start until this many clients registered")
      ->capture_default_str()
      ->check(ubersim::in_range(0, 2));
  if (const auto stop = ubersim::parse_command_line(app, argc, argv)) return *stop;

  ubersim::setup_logging("radio", options.common.verbosity());
  return ubersim::radio::run_radio(options);
}

}  // namespace

int main(int argc, char** argv) {
  return ubersim::run_main("ubersim_radio", [&] { return parse_and_run(argc, argv); });
}
