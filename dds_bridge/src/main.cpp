// ubersim_dds_bridge: ubersim's LCM channels on a Cyclone DDS domain, in the
// directions config/dds_bridge/<name>.cfg gives (see docs/dds_bridge.md).
#include <poll.h>

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "ubersim/cli.hpp"
#include "ubersim/config.hpp"
#include "ubersim/dds_bridge/bridge.hpp"
#include "ubersim/dds_bridge/bridge_config.hpp"
#include "ubersim/dds_bridge/dds_entity.hpp"
#include "ubersim/logging.hpp"
#include "ubersim/process_host.hpp"
#include "ubersim/process_main.hpp"
#include "ubersim/radio/radio_profile.hpp"
#include "ubersim/topics.hpp"

namespace {

struct Options {
  ubersim::CommonOptions common;
  int domain = 0;
  bool network = false;
  std::string config = "default";
  double truth_rate = 0;  // Hz of sim time; 0: every step
};

void log_start(const Options& options, const ubersim::dds::BridgeConfig& config,
               const ubersim::dds::Bridge& bridge) {
  spdlog::info(
      "config {}, DDS domain {} ({}), LCM {}; radio samples checked against the limits of radio "
      "profile {}",
      config.name, options.domain,
      ubersim::dds::cyclone_configured_by_environment() ? "Cyclone configured by CYCLONEDDS_URI"
      : options.network                                 ? "Cyclone's default network interface"
                                                        : "this host only, loopback",
      options.common.lcm_url, config.radio_limits);
  for (const std::string& line : bridge.describe_routes()) spdlog::info("{}", line);
  if (config.routes.empty()) spdlog::warn("config {} bridges no channel", config.name);
}

int run(const Options& options) {
  using namespace ubersim;
  const std::string config_dir = options.common.config_root();
  const dds::BridgeConfig config = dds::load_bridge_config(config_dir, options.config);
  const radio::CommandLimits limits =
      radio::load_radio_profile(config_dir, config.radio_limits).limits;

  ProcessHost host(options.common, "dds_bridge");
  const dds::CycloneLogToSpdlog cyclone_log;
  const dds::DdsParticipant participant =
      dds::join_domain(static_cast<dds_domainid_t>(options.domain),
                       options.network ? dds::DdsNetwork::Network : dds::DdsNetwork::Loopback);
  dds::Bridge bridge(config, host.channels(), limits, participant.get(), host.bus());
  log_start(options, config, bridge);

  const dds::Route* geometry = config.find(topics::kSimGeometry);
  if (geometry != nullptr && dds::carries_lcm_to_dds(geometry->direction))
    bridge.request_sim_geometry();
  // DDS's samples wait in Cyclone's reader cache; its listener signals wake_fd.
  host.bus().watch(bridge.wake_fd(), [&bridge] { bridge.take_dds(); });
  // A relay cannot know what its DDS readers need: with SIM_STATE bridged it
  // asks physics for every step, as DDS stacks got before states came on
  // demand, or for --truth-rate (docs/dds_bridge.md, docs/sync.md).
  const dds::Route* state_route = config.find(topics::kSimState);
  if (state_route != nullptr && dds::carries_lcm_to_dds(state_route->direction)) {
    if (options.truth_rate > 0) {
      host.ask_for_truth(periodic_demand(options.truth_rate));
    } else {
      host.ask_for_truth(every_step_demand());
    }
  }
  host.at_stop([&] {
    for (const std::string& line : bridge.summary()) spdlog::info("{}", line);
    spdlog::info("malformed LCM messages dropped: {}", host.bus().malformed_count());
  });
  return host.run(std::chrono::milliseconds(500));
}

int parse_and_run(int argc, char** argv) {
  Options options;
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
    return run(options);
  } catch (const ubersim::dds::DdsError& error) {
    spdlog::error("{}", error.what());  // in the log, with the rest of the bridge's lines
    return 1;
  }
}

}  // namespace

int main(int argc, char** argv) {
  return ubersim::run_main("ubersim_dds_bridge", [&] { return parse_and_run(argc, argv); });
}
