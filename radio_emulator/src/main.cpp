// ubersim_radio: the radio emulator process. Listens where each team's real
// radio server would (RADIO_YELLOW / RADIO_BLUE) and forwards what an
// emulated radio link lets through to physics on SIM_COMMANDS; returns the
// robots' feedback on RADIO_FEEDBACK_<TEAM>. See docs/radio.md.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <ubersim/truth_demand_t.hpp>
#include <vector>

#include "ubersim/cli.hpp"
#include "ubersim/config.hpp"
#include "ubersim/logging.hpp"
#include "ubersim/message_bus.hpp"
#include "ubersim/process_main.hpp"
#include "ubersim/radio/radio_emulator.hpp"
#include "ubersim/radio/radio_profile.hpp"
#include "ubersim/radio/sync_driver.hpp"
#include "ubersim/shutdown.hpp"

namespace {

struct Options {
  ubersim::CommonOptions common;
  std::string profile = "cmdragons02";
  std::string yellow_profile;
  std::string blue_profile;
  std::optional<std::uint64_t> seed;
  bool sync = false;
  ubersim::radio::SyncOptions sync_options;
};

int run(const Options& options) {
  using namespace ubersim;
  const std::string config_dir = options.common.config_root();
  const auto load = [&](const std::string& override_name) {
    return radio::load_radio_profile(config_dir,
                                     override_name.empty() ? options.profile : override_name);
  };
  const std::array<radio::RadioProfile, 2> profiles{load(options.yellow_profile),
                                                    load(options.blue_profile)};
  const ChannelNames channels = options.common.channels();

  ShutdownSignal shutdown;
  MessageBus bus(with_receive_buffer(options.common.lcm_url));
  const std::string commands_channel = channels(Channel::SimCommands);
  const std::array<std::string, 2> feedback_channels{channels.radio_feedback(Team::Yellow),
                                                     channels.radio_feedback(Team::Blue)};
  radio::RadioEmulator emulator(profiles, options.seed);
  const auto publish = [&](const radio::RadioEmulator::Output& out) {
    for (const sim_commands_t& message : out.commands) bus.publish(commands_channel, message);
    for (const auto& [team, message] : out.feedback) {
      bus.publish(feedback_channels[static_cast<int>(team)], message);
    }
  };

  bus.subscribe<sim_state_t>(channels(Channel::SimState), [&](const sim_state_t& state) {
    publish(emulator.on_sim_state(state, std::chrono::steady_clock::now()));
  });
  // What ground truth this emulator needs, for physics --truth-on-demand:
  // said whenever it changes and once a second, and first before any horizon
  // (physics in sync mode sends its first state after both).
  const std::string demand_channel = channels.extra(kTruthDemandChannel);
  // Compared as encoded bytes, in buffers kept across wakeups (no allocation
  // per message handled).
  std::vector<std::uint8_t> last_demand, demand_bytes;
  auto last_demand_wall = std::chrono::steady_clock::time_point{};
  const auto announce_demand = [&] {
    const truth_demand_t demand = emulator.truth_demand();
    const auto size = static_cast<std::size_t>(demand.getEncodedSize());
    demand_bytes.resize(size);
    demand.encode(demand_bytes.data(), 0, static_cast<int>(size));
    const auto now = std::chrono::steady_clock::now();
    if (demand_bytes == last_demand && now - last_demand_wall < std::chrono::seconds(1)) return;
    bus.publish_encoded(demand_channel, demand_bytes.data(), size);
    last_demand.swap(demand_bytes);
    last_demand_wall = now;
  };

  std::optional<radio::SyncDriver> sync;
  if (options.sync) sync.emplace(bus, channels, emulator, options.sync_options, publish);
  if (sync) {
    sync->before_release([&] {
      last_demand.clear();  // said again even if unchanged
      announce_demand();
    });
  }
  for (Team team : kTeams) {
    bus.subscribe<radio_packet_t>(channels.radio(team), [&, team](const radio_packet_t& p) {
      if (sync) {
        sync->on_packet(team, p);
      } else {
        publish(emulator.on_radio_packet(team, p, std::chrono::steady_clock::now()));
      }
    });
  }

  bus.subscribe<emulator_realism_t>(
      channels.emulator_realism(), [&](const emulator_realism_t& realism) {
        const std::string problem = emulator.apply_realism(realism);
        if (!problem.empty()) {
          emulator.warnings().warn(
              "realism", "ignored a realism change from '" + realism.sender + "': " + problem);
          return;
        }
        const auto& p = emulator.profile(Team::Blue);
        spdlog::info(
            "realism from '{}': command latency {} s, robot loss {}, feedback robot loss {}",
            realism.sender, p.command.latency, p.command.robot_loss, p.feedback.robot_loss);
      });

  for (Team team : kTeams) {
    const auto& p = profiles[static_cast<int>(team)];
    spdlog::info(
        "{}: {} -> {} with profile {} ({} Hz, latency {:.4f} s, jitter {:.4f} s, loss {} / robot "
        "{}, timeout {} s); feedback {} Hz on {}",
        team_name(team), channels.radio(team), commands_channel, p.name, p.max_packet_rate,
        p.command.latency, p.command.latency_jitter, p.command.packet_loss, p.command.robot_loss,
        p.command_timeout, p.feedback_rate, channels.radio_feedback(team));
  }
  spdlog::info("sim time from {}; LCM {}", channels(Channel::SimState), options.common.lcm_url);

  int status = 0;
  announce_demand();
  while (!shutdown.requested()) {
    bus.wait_and_handle(sync ? 50 : 200, &shutdown);
    announce_demand();
    if (sync && !sync->tick()) {
      status = 1;
      break;
    }
  }

  for (Team team : kTeams) spdlog::info("{}", emulator.summary(team));
  spdlog::info("malformed LCM messages dropped: {}; out-of-order SIM_STATEs ignored: {}",
               bus.malformed_count(), emulator.rejected_sim_states());
  if (sync) sync->log_summary();
  return status;
}

int parse_and_run(int argc, char** argv) {
  Options options;
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
  return run(options);
}

}  // namespace

int main(int argc, char** argv) {
  return ubersim::run_main("ubersim_radio", [&] { return parse_and_run(argc, argv); });
}
