#include "gc_link_shell.hpp"

#include <chrono>
#include <exception>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <ubersim/sim_control_ack_t.hpp>

#include "ubersim/field_side.hpp"
#include "ubersim/gc_link/ci_client.hpp"
#include "ubersim/gc_link/gc_link.hpp"
#include "ubersim/gc_link/gc_process.hpp"
#include "ubersim/process_host.hpp"
#include "ubersim/referee/event_log.hpp"
#include "ubersim/referee/robot_radii.hpp"
#include "ubersim/referee/sim_link.hpp"
#include "ubersim/spdlog.hpp"
#include "ubersim/topics.hpp"

namespace ubersim::gc_link {
namespace {

using std::chrono::milliseconds;

constexpr std::int64_t kRequestBase = 6LL << 56;  // our SIM_CONTROL ids, apart from others'

milliseconds ms(double seconds) {
  return milliseconds(static_cast<long>(seconds * 1000));
}

// The link's shell: the GcLink core and the game controller's CI client on
// the host (subscriptions, REFEREE and placements out, the event log, the
// result line; the game's end or the GC's failure stops the run).
class GcLinkShell {
 public:
  GcLinkShell(const GcLinkOptions& options, ProcessHost& host)
      : options_(options), host_(host), log_(options.events_file) {}

  int run() {
    // The game config first: its error ends the run at once (exit 2), not after physics answered.
    const auto rules = referee::load_game_config(options_.common.config_root(), options_.game);
    referee::SimLink sim(host_.bus(), host_.channels(), "ubersim_gc_link");
    field_ = sim.geometry(ms(options_.timeout_s));
    start_gc(rules);
    link_.emplace(link_options(rules), field_,
                  [this](const std::string& type) { return radii_(type); });
    MessageBus& bus = host_.bus();
    const ChannelNames& channels = host_.channels();
    subscribe(
        bus, channels, topics::kSimState, [this](const sim_state_t& s) { on_state(s); }, 100000);
    subscribe(bus, channels, topics::kSimGeometry,
              [this](const field_geometry_t& g) { on_geometry(g); });
    subscribe(bus, channels, topics::kSimControlAck, [](const sim_control_ack_t& ack) {
      if (ack.request_id >= kRequestBase && !ack.ok)
        spdlog::warn("physics refused a placement: {}", ack.message);
    });
    spdlog::info("official game controller on {} (CI mode): field {}, game {} s, publishing on {}",
                 address_, field_.name, half_length(rules) * 2,
                 channel_name(channels, topics::kReferee));
    wall_start_ = host_.now();
    // The game's end, or the GC's failure, ends the run after the wakeup that saw it.
    host_.after_wake([this](ProcessHost::Clock::time_point) {
      if (failed_) host_.stop(1);
      if (over_ && !options_.keep_running) host_.stop(0);
    });
    host_.at_stop([this] { finish(); });
    return host_.run(milliseconds(100));
  }

 private:
  double half_length(const referee::GameConfig& rules) const {
    const double length = options_.game_length > 0 ? options_.game_length : rules.game_length;
    return length / 2;
  }

  void start_gc(const referee::GameConfig& rules) {
    if (!options_.game_controller.empty()) {
      GcGame game{half_length(rules), options_.half_time, field_.field_length > 10.5};
      gc_process_.emplace(options_.game_controller, options_.gc_dir, game);
      address_ = gc_process_->ci_address();
    } else {
      address_ = options_.gc_address;
    }
    client_.emplace(address_, ms(options_.timeout_s));
  }

  LinkOptions link_options(const referee::GameConfig& rules) const {
    LinkOptions o;
    o.setup.yellow_name = options_.yellow_name;
    o.setup.blue_name = options_.blue_name;
    o.setup.yellow_keeper = rules.keeper_yellow;
    o.setup.blue_keeper = rules.keeper_blue;
    o.setup.division_a = field_.field_length > 10.5;
    o.setup.first_kickoff = rules.first_kickoff;
    o.setup.sides.yellow_defends = parse_defended_side(options_.yellow_defends);
    o.detectors = rules;
    o.tick_period = options_.tick_period;
    return o;
  }

  void on_geometry(const field_geometry_t& geometry) {
    if (geometry.field_length == field_.field_length &&
        geometry.field_width == field_.field_width && geometry.name == field_.name) {
      return;
    }
    field_ = geometry;
    if (link_) link_->set_field(field_);
  }

  void on_state(const sim_state_t& state) {
    if (over_ || failed_) return;
    try {
      auto conversation = link_->begin(state);
      if (conversation) client_->run(*conversation, ms(options_.timeout_s));
      publish(link_->finish(state, conversation ? &*conversation : nullptr));
    } catch (const std::exception& error) {
      std::cerr << "ubersim_gc_link: " << error.what() << "\n";
      failed_ = true;
    }
  }

  void publish(LinkOutput out) {
    for (const std::string& line : out.log_lines) log_.write(line);
    if (out.placement) {
      out.placement->request_id = kRequestBase + next_request_++;
      out.placement->sender = "ubersim_gc_link";
      ubersim::publish(host_.bus(), host_.channels(), topics::kSimControl, *out.placement);
    }
    if (out.referee)
      ubersim::publish(host_.bus(), host_.channels(), topics::kReferee, *out.referee);
    if (out.game_over) over_ = true;
  }

  void finish() {
    const double wall = std::chrono::duration<double>(host_.now() - wall_start_).count();
    if (!link_) return;
    log_.write(link_->result_line(wall));
    const Referee& gc = link_->gc();
    std::cout << "result: yellow " << gc.yellow().score() << " : " << gc.blue().score() << " blue ("
              << (over_ ? "game over" : "stopped") << " at " << link_->last_time()
              << " s sim time, " << wall << " s wall time, " << link_->ticks()
              << " game controller ticks, " << link_->judged() << " states judged, "
              << link_->reports() << " events reported"
              << (link_->forced_restarts() > 0
                      ? ", " + std::to_string(link_->forced_restarts()) +
                            " restarts forced by the operator (see the warnings above)"
                      : std::string())
              << ")" << std::endl;
  }

  const GcLinkOptions& options_;
  ProcessHost& host_;
  referee::EventLog log_;
  field_geometry_t field_{};
  std::optional<GcProcess> gc_process_;
  std::optional<CiClient> client_;
  std::string address_;
  std::optional<GcLink> link_;
  referee::RobotRadii radii_{options_.common.config_root()};
  std::int64_t next_request_ = 0;
  bool over_ = false;
  bool failed_ = false;
  std::chrono::steady_clock::time_point wall_start_ = std::chrono::steady_clock::now();
};

}  // namespace

int run_gc_link(const GcLinkOptions& options) {
  ProcessHost host(options.common, "gc_link");
  GcLinkShell shell(options, host);
  return shell.run();
}

}  // namespace ubersim::gc_link
