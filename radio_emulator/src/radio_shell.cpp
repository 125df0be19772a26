#include "radio_shell.hpp"

#include <array>
#include <chrono>
#include <functional>
#include <ubersim/emulator_realism_t.hpp>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <ubersim/sync_client_t.hpp>
#include <ubersim/vision_schedule_t.hpp>

#include "ubersim/logging.hpp"
#include "ubersim/process_host.hpp"
#include "ubersim/radio/radio_emulator.hpp"
#include "ubersim/radio/radio_profile.hpp"
#include "ubersim/topics.hpp"

namespace ubersim::radio {
namespace {

using Profiles = std::array<RadioProfile, 2>;

Profiles load_profiles(const RadioOptions& options) {
  const std::string config_dir = options.common.config_root();
  const auto load = [&](const std::string& override_name) {
    return load_radio_profile(config_dir, override_name.empty() ? options.profile : override_name);
  };
  return {load(options.yellow_profile), load(options.blue_profile)};
}

// What the links let through goes out on SIM_COMMANDS and RADIO_FEEDBACK_<TEAM>,
// in the order the core gave it.
class LinkOutputs {
 public:
  explicit LinkOutputs(ProcessHost& host)
      : commands_(host.bus(), host.channels(), topics::kSimCommands),
        feedback_{{{host.bus(), host.channels(), topics::kRadioFeedback.of(Team::Yellow)},
                   {host.bus(), host.channels(), topics::kRadioFeedback.of(Team::Blue)}}} {}
  void operator()(const RadioEmulator::Output& out) const {
    for (const sim_commands_t& message : out.commands) commands_(message);
    for (const auto& [team, message] : out.feedback) feedback_[static_cast<int>(team)](message);
  }
  const std::string& commands_channel() const { return commands_.channel(); }

 private:
  Publisher<sim_commands_t> commands_;
  std::array<Publisher<radio_feedback_t>, 2> feedback_;
};

// The radio's shell: the emulator core (and in sync mode its SyncDriver) on
// the host, what each message does, the truth demand, the summary at stop.
class RadioShell {
 public:
  RadioShell(const RadioOptions& options, const Profiles& profiles, ProcessHost& host)
      : options_(options),
        profiles_(profiles),
        host_(host),
        emulator_(profiles, options.seed),
        publish_(host) {
    if (options.sync) {
      sync_.emplace(host.bus(), host.channels(), emulator_, options.sync_options,
                    std::cref(publish_));
    }
  }
  RadioShell(const RadioShell&) = delete;
  RadioShell& operator=(const RadioShell&) = delete;

  int run();

 private:
  void subscribe_inputs();
  void on_realism(const emulator_realism_t& realism);
  void log_links() const;
  void log_summary() const;

  const RadioOptions& options_;
  const Profiles& profiles_;
  ProcessHost& host_;
  RadioEmulator emulator_;
  const LinkOutputs publish_;
  std::optional<SyncDriver> sync_;
};

int RadioShell::run() {
  subscribe_inputs();
  // What ground truth this emulator needs, for physics' truth on demand: said
  // whenever it changes and once a second, first before the first wait; in
  // sync mode said again right before the first horizon that lets physics
  // start (physics sends its first state after both).
  host_.ask_for_truth([this] { return emulator_.truth_demand(); });
  if (sync_) {
    sync_->before_release([this] { host_.send_truth_demand(host_.now()); });
    sync_->before_horizon(
        [this](ProcessHost::Clock::time_point now) { host_.renew_truth_demand(now); });
    host_.after_wake([this](ProcessHost::Clock::time_point now) {
      if (!sync_->tick(now)) host_.stop(1);  // a client dropped with --sync-strict
    });
  }
  log_links();
  host_.at_stop([this] { log_summary(); });
  return host_.run(sync_ ? std::chrono::milliseconds(50) : std::chrono::milliseconds(200));
}

// The emulator's input: SIM_STATE, the teams' radio packets (in sync mode the
// clients' answers) and realism changes, each stamped with the host's clock.
void RadioShell::subscribe_inputs() {
  MessageBus& bus = host_.bus();
  const ChannelNames& channels = host_.channels();
  subscribe(bus, channels, topics::kSimState, [this](const sim_state_t& state) {
    if (sync_) {
      sync_->on_sim_state(state, host_.now());
    } else {
      publish_(emulator_.on_sim_state(state, host_.now()));
    }
  });
  if (sync_) {
    subscribe(bus, channels, topics::kSyncClient,
              [this](const sync_client_t& message) { sync_->on_client(message, host_.now()); });
    subscribe(bus, channels, topics::kVisionSchedule, [this](const vision_schedule_t& schedule) {
      sync_->on_schedule(schedule, host_.now());
    });
  }
  for (Team team : kTeams) {
    subscribe(bus, channels, topics::kRadio.of(team), [this, team](const radio_packet_t& packet) {
      if (sync_) {
        sync_->on_packet(team, packet, host_.now());
      } else {
        publish_(emulator_.on_radio_packet(team, packet, host_.now()));
      }
    });
  }
  subscribe(bus, channels, topics::kEmulatorRealism,
            [this](const emulator_realism_t& realism) { on_realism(realism); });
}

// A run-time realism change (EMULATOR_REALISM): applied, or ignored with the reason.
void RadioShell::on_realism(const emulator_realism_t& realism) {
  const std::string problem = emulator_.apply_realism(realism);
  if (!problem.empty()) {
    emulator_.warnings().warn("realism",
                              "ignored a realism change from '" + realism.sender + "': " + problem);
    return;
  }
  const auto& p = emulator_.profile(Team::Blue);
  spdlog::info("realism from '{}': command latency {} s, robot loss {}, feedback robot loss {}",
               realism.sender, p.command.latency, p.command.robot_loss, p.feedback.robot_loss);
}

void RadioShell::log_links() const {
  for (Team team : kTeams) {
    const auto& p = profiles_[static_cast<int>(team)];
    spdlog::info(
        "{}: {} -> {} with profile {} ({} Hz, latency {:.4f} s, jitter {:.4f} s, loss {} / robot "
        "{}, timeout {} s); feedback {} Hz on {}",
        team_name(team), channel_name(host_.channels(), topics::kRadio.of(team)),
        publish_.commands_channel(), p.name, p.max_packet_rate, p.command.latency,
        p.command.latency_jitter, p.command.packet_loss, p.command.robot_loss, p.command_timeout,
        p.feedback_rate, channel_name(host_.channels(), topics::kRadioFeedback.of(team)));
  }
  spdlog::info("sim time from {}; LCM {}", channel_name(host_.channels(), topics::kSimState),
               options_.common.lcm_url);
}

void RadioShell::log_summary() const {
  for (Team team : kTeams) spdlog::info("{}", emulator_.summary(team));
  spdlog::info("malformed LCM messages dropped: {}; out-of-order SIM_STATEs ignored: {}",
               host_.bus().malformed_count(), emulator_.rejected_sim_states());
  if (sync_) sync_->log_summary();
}

}  // namespace

int run_radio(const RadioOptions& options) {
  const Profiles profiles = load_profiles(options);
  ProcessHost host(options.common, "radio");
  RadioShell shell(options, profiles, host);
  return shell.run();
}

}  // namespace ubersim::radio
