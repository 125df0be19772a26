// ubersim_gc_link: the official ssl-game-controller referees a sync-mode game
// through its CI port, with simulation time as its clock (docs/official_gc.md).
// Exit status: 0 game over (or stopped by a signal), 1 the GC failed, 2 bad usage or a config
// error.
#include <CLI/CLI.hpp>
#include <chrono>
#include <fstream>
#include <iostream>
#include <optional>
#include <ubersim/sim_control_ack_t.hpp>

#include "ubersim/cli.hpp"
#include "ubersim/field_side.hpp"
#include "ubersim/gc_link/ci_client.hpp"
#include "ubersim/gc_link/gc_link.hpp"
#include "ubersim/gc_link/gc_process.hpp"
#include "ubersim/logging.hpp"
#include "ubersim/process_host.hpp"
#include "ubersim/process_main.hpp"
#include "ubersim/referee/robot_radii.hpp"
#include "ubersim/referee/sim_link.hpp"
#include "ubersim/topics.hpp"

namespace {

using namespace ubersim;
using namespace ubersim::gc_link;
using std::chrono::milliseconds;

constexpr std::int64_t kRequestBase = 6LL << 56;  // our SIM_CONTROL ids, apart from others'

struct Options {
  CommonOptions common;
  std::string game_controller;  // binary to start, or empty
  std::string gc_address;       // a GC already running in CI mode, or empty
  std::string gc_dir = "gc";    // the started GC's folder
  std::string game = "division_b";
  double game_length = 0;      // s, both halves; 0: the game config's
  double half_time = 5;        // s of break
  double tick_period = 0.025;  // s
  double timeout_s = 10;       // for physics, the GC's start and each answer
  std::string yellow_name = "Yellow", blue_name = "Blue";
  std::string yellow_defends = "negative";
  std::string events_file;
  bool keep_running = false;
};

milliseconds ms(double seconds) {
  return milliseconds(static_cast<long>(seconds * 1000));
}

class Runner {
 public:
  Runner(const Options& options, ProcessHost& host) : options_(options), host_(host) {
    if (!options.events_file.empty()) {
      log_.open(options.events_file);
      if (!log_) throw std::runtime_error("cannot write the event log " + options.events_file);
    }
  }

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
    for (const std::string& line : out.log_lines) write(line);
    if (out.placement) {
      out.placement->request_id = kRequestBase + next_request_++;
      out.placement->sender = "ubersim_gc_link";
      ubersim::publish(host_.bus(), host_.channels(), topics::kSimControl, *out.placement);
    }
    if (out.referee)
      ubersim::publish(host_.bus(), host_.channels(), topics::kReferee, *out.referee);
    if (out.game_over) over_ = true;
  }

  void write(const std::string& line) {
    if (log_.is_open()) log_ << line << "\n" << std::flush;
  }

  void finish() {
    const double wall = std::chrono::duration<double>(host_.now() - wall_start_).count();
    if (!link_) return;
    write(link_->result_line(wall));
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

  const Options& options_;
  ProcessHost& host_;
  std::ofstream log_;
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

int parse_and_run(int argc, char** argv) {
  Options o;
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
  ProcessHost host(o.common, "gc_link");
  Runner runner(o, host);
  return runner.run();
}

}  // namespace

int main(int argc, char** argv) {
  return ubersim::run_main("ubersim_gc_link", [&] { return parse_and_run(argc, argv); });
}
