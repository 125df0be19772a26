// ubersim_radio: the radio emulator process. Listens where each team's real
// radio server would (RADIO_YELLOW / RADIO_BLUE) and forwards what an
// emulated radio link lets through to physics on SIM_COMMANDS; returns the
// robots' feedback on RADIO_FEEDBACK_<TEAM>. See docs/radio.md.
#include <CLI/CLI.hpp>
#include <array>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <ubersim/emulator_realism_t.hpp>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <ubersim/sync_client_t.hpp>
#include <ubersim/vision_schedule_t.hpp>

#include "ubersim/cli.hpp"
#include "ubersim/config.hpp"
#include "ubersim/logging.hpp"
#include "ubersim/process_host.hpp"
#include "ubersim/process_main.hpp"
#include "ubersim/radio/radio_emulator.hpp"
#include "ubersim/radio/radio_profile.hpp"
#include "ubersim/radio/sync_driver.hpp"
#include "ubersim/topics.hpp"

namespace {

using ubersim::ProcessHost;
using ubersim::Team;
using ubersim::radio::RadioEmulator;
using ubersim::radio::SyncDriver;

struct Options {
  ubersim::CommonOptions common;
  std::string profile = "cmdragons02";
  std::string yellow_profile;
  std::string blue_profile;
  std::optional<std::uint64_t> seed;
  bool sync = false;
  ubersim::radio::SyncOptions sync_options;
};

std::array<ubersim::radio::RadioProfile, 2> load_profiles(const Options& options) {
  const std::string config_dir = options.common.config_root();
  const auto load = [&](const std::string& override_name) {
    return ubersim::radio::load_radio_profile(
        config_dir, override_name.empty() ? options.profile : override_name);
  };
  return {load(options.yellow_profile), load(options.blue_profile)};
}

// What the links let through goes out on SIM_COMMANDS and RADIO_FEEDBACK_<TEAM>,
// in the order the core gave it.
class LinkOutputs {
 public:
  explicit LinkOutputs(ProcessHost& host)
      : commands_(host.bus(), host.channels(), ubersim::topics::kSimCommands),
        feedback_{{{host.bus(), host.channels(), ubersim::topics::kRadioFeedback.of(Team::Yellow)},
                   {host.bus(), host.channels(), ubersim::topics::kRadioFeedback.of(Team::Blue)}}} {
  }
  void operator()(const RadioEmulator::Output& out) const {
    for (const ubersim::sim_commands_t& message : out.commands) commands_(message);
    for (const auto& [team, message] : out.feedback) feedback_[static_cast<int>(team)](message);
  }
  const std::string& commands_channel() const { return commands_.channel(); }

 private:
  ubersim::Publisher<ubersim::sim_commands_t> commands_;
  std::array<ubersim::Publisher<ubersim::radio_feedback_t>, 2> feedback_;
};

// A run-time realism change (EMULATOR_REALISM): applied, or ignored with the reason.
void on_realism(RadioEmulator& emulator, const ubersim::emulator_realism_t& realism) {
  const std::string problem = emulator.apply_realism(realism);
  if (!problem.empty()) {
    emulator.warnings().warn("realism",
                             "ignored a realism change from '" + realism.sender + "': " + problem);
    return;
  }
  const auto& p = emulator.profile(Team::Blue);
  spdlog::info("realism from '{}': command latency {} s, robot loss {}, feedback robot loss {}",
               realism.sender, p.command.latency, p.command.robot_loss, p.feedback.robot_loss);
}

// The emulator's input: SIM_STATE, the teams' radio packets (in sync mode the
// clients' answers) and realism changes, each stamped with the host's clock.
void subscribe_inputs(ProcessHost& host, RadioEmulator& emulator, std::optional<SyncDriver>& sync,
                      const LinkOutputs& publish) {
  using namespace ubersim;
  subscribe(host.bus(), host.channels(), topics::kSimState,
            [&](const sim_state_t& state) { publish(emulator.on_sim_state(state, host.now())); });
  if (sync) {
    subscribe(host.bus(), host.channels(), topics::kSyncClient,
              [&](const sync_client_t& message) { sync->on_client(message, host.now()); });
    subscribe(host.bus(), host.channels(), topics::kVisionSchedule,
              [&](const vision_schedule_t& schedule) { sync->on_schedule(schedule, host.now()); });
  }
  for (Team team : kTeams) {
    subscribe(host.bus(), host.channels(), topics::kRadio.of(team),
              [&, team](const radio_packet_t& packet) {
                if (sync) {
                  sync->on_packet(team, packet, host.now());
                } else {
                  publish(emulator.on_radio_packet(team, packet, host.now()));
                }
              });
  }
  subscribe(host.bus(), host.channels(), topics::kEmulatorRealism,
            [&](const emulator_realism_t& realism) { on_realism(emulator, realism); });
}

void log_links(const ProcessHost& host, const Options& options,
               const std::array<ubersim::radio::RadioProfile, 2>& profiles,
               const LinkOutputs& outputs) {
  using namespace ubersim;
  for (Team team : kTeams) {
    const auto& p = profiles[static_cast<int>(team)];
    spdlog::info(
        "{}: {} -> {} with profile {} ({} Hz, latency {:.4f} s, jitter {:.4f} s, loss {} / robot "
        "{}, timeout {} s); feedback {} Hz on {}",
        team_name(team), channel_name(host.channels(), topics::kRadio.of(team)),
        outputs.commands_channel(), p.name, p.max_packet_rate, p.command.latency,
        p.command.latency_jitter, p.command.packet_loss, p.command.robot_loss, p.command_timeout,
        p.feedback_rate, channel_name(host.channels(), topics::kRadioFeedback.of(team)));
  }
  spdlog::info("sim time from {}; LCM {}", channel_name(host.channels(), topics::kSimState),
               options.common.lcm_url);
}

void log_summary(ProcessHost& host, const RadioEmulator& emulator,
                 const std::optional<SyncDriver>& sync) {
  for (Team team : ubersim::kTeams) spdlog::info("{}", emulator.summary(team));
  spdlog::info("malformed LCM messages dropped: {}; out-of-order SIM_STATEs ignored: {}",
               host.bus().malformed_count(), emulator.rejected_sim_states());
  if (sync) sync->log_summary();
}

// The wiring block: the emulator core, in sync mode its SyncDriver, and what
// the host is given (docs/design.md, "The process host").
int run(const Options& options) {
  using namespace ubersim;
  const std::array<radio::RadioProfile, 2> profiles = load_profiles(options);
  ProcessHost host(options.common, "radio");
  RadioEmulator emulator(profiles, options.seed);
  const LinkOutputs publish(host);
  std::optional<SyncDriver> sync;
  if (options.sync) {
    sync.emplace(host.bus(), host.channels(), emulator, options.sync_options, std::cref(publish));
  }
  subscribe_inputs(host, emulator, sync, publish);

  // What ground truth this emulator needs, for physics' truth on demand: said
  // whenever it changes and once a second, first before the first wait; in
  // sync mode said again right before the first horizon that lets physics
  // start (physics sends its first state after both).
  host.ask_for_truth([&] { return emulator.truth_demand(); });
  if (sync) {
    sync->before_release([&] { host.send_truth_demand(host.now()); });
    host.after_wake([&](ProcessHost::Clock::time_point now) {
      if (!sync->tick(now)) host.stop(1);  // a client dropped with --sync-strict
    });
  }
  log_links(host, options, profiles, publish);
  host.at_stop([&] { log_summary(host, emulator, sync); });
  return host.run(sync ? std::chrono::milliseconds(50) : std::chrono::milliseconds(200));
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
