#include "ubersim/physics/physics_shell.hpp"

#include "ubersim/topics.hpp"

namespace ubersim::physics {
namespace {

using Clock = Pacing::Clock;

double seconds_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

Clock::duration wall_duration(double seconds) {
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
}

// SIM_VISION_SCHEDULE wakes physics in sync mode, with --wait-for-vision and
// as fast as possible: there it must know at once that a vision emulator
// listens, and how far it has got (it waits for it). Started in real time it
// need not wake for the vision's schedules: it reads them when it wakes anyway
// (for its next state), long before a switch to sync; switched to as fast as
// possible at run time, it looks for them every millisecond while it waits.
bool schedule_wakes(const ShellOptions& options) {
  return options.sync || options.wait_for_vision || options.speed == 0;
}

PacingOptions pacing_options(const WorldSetup& setup, const ShellOptions& options) {
  PacingOptions pacing;
  pacing.poll_period = wall_duration(setup.physics.message_poll_period);
  pacing.max_pacing_lag = setup.physics.max_pacing_lag;
  pacing.schedule_wakes = schedule_wakes(options);
  return pacing;
}

}  // namespace

PhysicsShell::PhysicsShell(WorldSetup setup, ProcessHost& host, ShellOptions options)
    : host_(host),
      options_(std::move(options)),
      core_(std::move(setup), options_),
      publisher_(host.bus(), host.channels()),
      pacing_(core_, publisher_, stats_, stepping_clock_,
              pacing_options(core_.world().setup(), options_)) {
  subscribe();
}

void PhysicsShell::subscribe() {
  MessageBus& bus = host_.bus();
  const ChannelNames& channels = host_.channels();
  if (options_.sync_referee) {
    ubersim::subscribe(bus, channels, topics::kReferee,
                       [this](const referee_t& r) { core_.on_referee(r); });
  }
  ubersim::subscribe(bus, channels, topics::kSyncHorizon, [this](const sync_horizon_t& h) {
    core_.on_sync_horizon(h);
    pacing_.on_sync_horizon(h);
  });
  if (options_.truth_on_demand) {
    ubersim::subscribe(bus, channels, topics::kTruthDemand,
                       [this](const truth_demand_t& d) { core_.on_truth_demand(d, host_.now()); });
  }
  const auto on_schedule = [this](const vision_schedule_t& schedule) {
    pacing_.on_vision_schedule(schedule, host_.now());
  };
  if (schedule_wakes(options_)) {
    ubersim::subscribe(bus, channels, topics::kVisionSchedule, on_schedule);
  } else {
    ubersim::subscribe_unhurried(bus, channels, topics::kVisionSchedule, on_schedule);
  }
  // A command waits in the world until its t_apply, and physics reads the bus
  // before it runs any step, so a command need not wake it: read it when
  // something else does (a due state, a demand, a request, a horizon, which
  // the radio sends after the commands it covers).
  ubersim::subscribe_unhurried(bus, channels, topics::kSimCommands,
                               [this](const sim_commands_t& p) { core_.on_commands(p); });
  ubersim::subscribe(bus, channels, topics::kSimControl, [this](const sim_control_t& r) {
    publisher_.publish(core_.on_control(r, host_.dropped_input()));
  });
}

void PhysicsShell::add_timers() {
  const auto period = wall_duration(core_.world().setup().physics.geometry_publish_period);
  host_.every(period, [this](Clock::time_point) {
    if (core_.duration_reached()) return;  // the run is over: nothing more goes out
    stepping_clock_.run_ends();
    publisher_.publish_geometry(core_.geometry());
    // Late joiners learn the time while nothing moves.
    if (core_.idle()) publisher_.publish(core_.state());
  });
  host_.every(period, [this](Clock::time_point now) { core_.expire_demand(now); });
}

ServerStats PhysicsShell::stats() const {
  ServerStats s = stats_;
  s.steps = core_.steps();
  s.states_published = core_.states_published();
  s.demand_late = core_.demand_late();
  s.controls_handled = core_.controls_handled();
  s.packets_received = core_.packets_received();
  s.vision_silences = pacing_.vision().silences();
  return s;
}

int PhysicsShell::run() {
  const auto start = host_.now();
  publisher_.publish_geometry(core_.geometry());
  // Sync mode, and --wait-for-vision: the first state once the others listen.
  pacing_.start(start, core_.sync() || options_.wait_for_vision);
  add_timers();
  log_start();
  host_.at_stop([this, start] { log_stop(start); });
  return host_.run(pacing_);
}

void PhysicsShell::log_start() const {
  const World& world = core_.world();
  spdlog::info("physics running: scenario {} on field {} ({:g} x {:g} m), {} robots, {} Hz, {}{}",
               options_.scenario, world.setup().field.name, world.setup().field.field_length,
               world.setup().field.field_width, world.robots().size(), 1.0 / world.dt(),
               core_.sync()                  ? std::string("sync (docs/sync.md)")
               : core_.lockstep()            ? std::string("lockstep")
               : core_.as_fast_as_possible() ? std::string("as fast as possible")
                                             : fmt::format("{:g} x real time", core_.speed()),
               core_.paused() ? ", paused" : "");
}

void PhysicsShell::log_stop(Clock::time_point start) {
  const World& world = core_.world();
  const auto end = host_.now();
  pacing_.finish(end);
  stats_.wall_seconds = seconds_between(start, end);
  if (options_.truth_on_demand) {
    spdlog::info(
        "truth on demand: {} states published for {} steps; {} demanded instants came late",
        core_.states_published(), core_.steps(), core_.demand_late());
  }
  const bool paced = core_.paced() && !core_.sync();
  stats_.drift = paced && !core_.paused() ? pacing_.drift(end) : 0;
  const auto first_state = pacing_.gate().first_state_wall();
  if ((options_.sync || options_.wait_for_vision) && first_state) {
    // The start, waiting for the others to listen, left out.
    stats_.sync_run_seconds = seconds_between(*first_state, end);
    spdlog::info("{}: {:.3f} s of sim time in {:.3f} s of wall time from the first state",
                 options_.sync ? "sync" : "as fast as possible", world.time(),
                 stats_.sync_run_seconds);
  }
  log_waits();
  spdlog::info("{}", command_summary(world.counters()));
  if (stepping_clock_.seconds() > 0) {
    spdlog::info("stepping took {:.3f} s of CPU ({:.2f} % of one core over the run)",
                 stepping_clock_.seconds(), 100 * stepping_clock_.seconds() / stats_.wall_seconds);
  }
  spdlog::info(
      "physics stopping: {} steps, {:.3f} s of sim time in {:.3f} s of wall time{}", core_.steps(),
      world.time(), stats_.wall_seconds,
      paced ? fmt::format(", {:+.1f} ms from the schedule", stats_.drift * 1e3) : std::string());
}

void PhysicsShell::log_waits() const {
  if (core_.sync() || !stats_.sync_waits.empty()) {
    double total = 0;
    for (const auto& [name, seconds] : stats_.sync_wait_seconds) total += seconds;
    spdlog::info("sync: waited {:.3f} s of wall time at the horizon", total);
    for (const auto& [name, seconds] : stats_.sync_wait_seconds) {
      spdlog::info("sync: waited {:.3f} s for {} ({} waits)", seconds, name,
                   stats_.sync_waits.at(name));
    }
  }
  const std::int64_t silences = pacing_.vision().silences();
  if (stats_.vision_waits > 0 || silences > 0) {
    spdlog::info(
        "as fast as possible: waited {:.3f} s of wall time for the vision emulator ({} waits, "
        "{} states sent for it); it fell silent {} times",
        stats_.vision_wait_seconds, stats_.vision_waits, stats_.states_for_vision, silences);
  }
}

}  // namespace ubersim::physics
