// ubersim_dds_bridge: ubersim's LCM channels on a Cyclone DDS domain, in the
// directions config/dds_bridge/<name>.cfg gives (see docs/dds_bridge.md); its
// shell (DdsBridgeShell) is dds_bridge_shell.cpp.
#include <CLI/CLI.hpp>

#include "dds_bridge_shell.hpp"
#include "ubersim/cli.hpp"
#include "ubersim/dds_bridge/dds_entity.hpp"
#include "ubersim/logging.hpp"
#include "ubersim/process_main.hpp"

namespace {

int parse_and_run(int argc, char** argv) {
  ubersim::dds::DdsBridgeOptions options;
  CLI::App app{"ubersim DDS bridge: LCM channels <-> Cyclone DDS topics"};
  ubersim::add_common_options(app, options.common);
  app.add_option("--domain", options.domain, "DDS domain id")
      ->check(ubersim::in_range(0, 232))
      ->capture_default_str();
  app.add_flag("--network", options.network,
               "let DDS use Cyclone's default network interface (default: loopback only, as "
               "LCM's ttl=0; CYCLONEDDS_URI, when set, always decides)");
  app.add_option("--config", options.config,
                 "bridge config: config/dds_bridge/NAME.cfg or a path to a .cfg file")
      ->capture_default_str();
  app.add_option("--truth-rate", options.truth_rate,
                 "SIM_STATE states per second of sim time to ask physics for, when SIM_STATE is "
                 "bridged to DDS (0 = every step)")
      ->check(ubersim::at_least(0))
      ->capture_default_str();
  if (const auto stop = ubersim::parse_command_line(app, argc, argv)) return *stop;

  ubersim::setup_logging("dds_bridge", options.common.verbosity());
  try {
    return ubersim::dds::run_dds_bridge(options);
  } catch (const ubersim::dds::DdsError& error) {
    spdlog::error("{}", error.what());  // in the log, with the rest of the bridge's lines
    return 1;
  }
}

}  // namespace

int main(int argc, char** argv) {
  return ubersim::run_main("ubersim_dds_bridge", [&] { return parse_and_run(argc, argv); });
}
