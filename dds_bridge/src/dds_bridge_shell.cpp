#include "dds_bridge_shell.hpp"

#include <chrono>

#include "ubersim/config.hpp"
#include "ubersim/dds_bridge/bridge.hpp"
#include "ubersim/dds_bridge/bridge_config.hpp"
#include "ubersim/dds_bridge/dds_entity.hpp"
#include "ubersim/logging.hpp"
#include "ubersim/process_host.hpp"
#include "ubersim/radio/radio_profile.hpp"
#include "ubersim/spdlog.hpp"
#include "ubersim/topics.hpp"

namespace ubersim::dds {
namespace {

// The DDS bridge's shell: its domain participant and the Bridge on the host
// (the bus watching the bridge's wake fd, the truth demand, the summary).
class DdsBridgeShell {
 public:
  DdsBridgeShell(const DdsBridgeOptions& options, const BridgeConfig& config,
                 const radio::CommandLimits& limits, ProcessHost& host)
      : options_(options),
        config_(config),
        host_(host),
        participant_(join_domain(static_cast<dds_domainid_t>(options.domain),
                                 options.network ? DdsNetwork::Network : DdsNetwork::Loopback)),
        bridge_(config, host.channels(), limits, participant_.get(), host.bus()) {}
  DdsBridgeShell(const DdsBridgeShell&) = delete;
  DdsBridgeShell& operator=(const DdsBridgeShell&) = delete;

  int run();

 private:
  void ask_for_truth();
  void log_start() const;

  const DdsBridgeOptions& options_;
  const BridgeConfig& config_;
  ProcessHost& host_;
  const CycloneLogToSpdlog cyclone_log_;
  const DdsParticipant participant_;
  Bridge bridge_;
};

int DdsBridgeShell::run() {
  log_start();
  const Route* geometry = config_.find(topics::kSimGeometry);
  if (geometry != nullptr && carries_lcm_to_dds(geometry->direction))
    bridge_.request_sim_geometry();
  // DDS's samples wait in Cyclone's reader cache; its listener signals wake_fd.
  host_.bus().watch(bridge_.wake_fd(), [this] { bridge_.take_dds(); });
  ask_for_truth();
  host_.at_stop([this] {
    for (const std::string& line : bridge_.summary()) spdlog::info("{}", line);
    spdlog::info("malformed LCM messages dropped: {}", host_.bus().malformed_count());
  });
  return host_.run(std::chrono::milliseconds(500));
}

// A relay cannot know what its DDS readers need: with SIM_STATE bridged it
// asks physics for every step, as DDS stacks got before states came on
// demand, or for --truth-rate (docs/dds_bridge.md, docs/sync.md).
void DdsBridgeShell::ask_for_truth() {
  const Route* state_route = config_.find(topics::kSimState);
  if (state_route == nullptr || !carries_lcm_to_dds(state_route->direction)) return;
  if (options_.truth_rate > 0) {
    host_.ask_for_truth(periodic_demand(options_.truth_rate));
  } else {
    host_.ask_for_truth(every_step_demand());
  }
}

void DdsBridgeShell::log_start() const {
  spdlog::info(
      "config {}, DDS domain {} ({}), LCM {}; radio samples checked against the limits of radio "
      "profile {}",
      config_.name, options_.domain,
      cyclone_configured_by_environment() ? "Cyclone configured by CYCLONEDDS_URI"
      : options_.network                  ? "Cyclone's default network interface"
                                          : "this host only, loopback",
      options_.common.lcm_url, config_.radio_limits);
  for (const std::string& line : bridge_.describe_routes()) spdlog::info("{}", line);
  if (config_.routes.empty()) spdlog::warn("config {} bridges no channel", config_.name);
}

}  // namespace

int run_dds_bridge(const DdsBridgeOptions& options) {
  const std::string config_dir = options.common.config_root();
  const BridgeConfig config = load_bridge_config(config_dir, options.config);
  const radio::CommandLimits limits =
      radio::load_radio_profile(config_dir, config.radio_limits).limits;
  ProcessHost host(options.common, "dds_bridge");
  DdsBridgeShell shell(options, config, limits, host);
  return shell.run();
}

}  // namespace ubersim::dds
