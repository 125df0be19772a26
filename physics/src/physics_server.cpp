#include "ubersim/physics/physics_server.hpp"

#include <ubersim/referee_t.hpp>
#include <ubersim/truth_demand_t.hpp>
#include <ubersim/vision_schedule_t.hpp>

#include "ubersim/shutdown.hpp"

namespace ubersim::physics {
namespace {

using Clock = Pacer::Clock;

double seconds_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

}  // namespace

PhysicsServer::PhysicsServer(WorldSetup setup, MessageBus& bus, const ChannelNames& channels,
                             ServerOptions options)
    : core_(std::move(setup), options),
      bus_(bus),
      state_channel_(channels(Channel::SimState)),
      geometry_channel_(channels(Channel::SimGeometry)),
      ack_channel_(channels(Channel::SimControlAck)),
      options_(std::move(options)),
      schedule_wakes_(options_.sync || options_.wait_for_vision || options_.speed == 0) {
  if (options_.sync_referee) {
    bus_.subscribe<referee_t>(channels.referee(),
                              [this](const referee_t& r) { core_.on_referee(r); });
  }
  bus_.subscribe<sync_horizon_t>(channels.extra(kSyncHorizonChannel),
                                 [this](const sync_horizon_t& h) { core_.on_sync_horizon(h); });
  if (options_.truth_on_demand) {
    bus_.subscribe<truth_demand_t>(
        channels.extra(kTruthDemandChannel),
        [this](const truth_demand_t& d) { core_.on_truth_demand(d, Clock::now()); });
  }
  // Physics needs to know that a vision emulator is listening, before its
  // first state in sync mode, and as fast as possible how far it has got (it
  // waits for it there). Started in real time it need not wake for the
  // vision's schedules: it reads them when it wakes anyway (for its next
  // state), long before a switch to sync; switched to as fast as possible at
  // run time, it looks for them every millisecond while it waits.
  const auto on_schedule = [this](const vision_schedule_t& schedule) {
    core_.on_vision_schedule(schedule, Clock::now());
  };
  if (schedule_wakes_) {
    bus_.subscribe<vision_schedule_t>(channels.extra(kVisionScheduleChannel), on_schedule);
  } else {
    bus_.subscribe_unhurried<vision_schedule_t>(channels.extra(kVisionScheduleChannel),
                                                on_schedule);
  }
  // A command waits in the world until its t_apply, and physics reads the bus
  // before it runs any step, so a command need not wake it: read it when
  // something else does (a due state, a demand, a request, a horizon, which
  // the radio sends after the commands it covers).
  bus_.subscribe_unhurried<sim_commands_t>(
      channels(Channel::SimCommands), [this](const sim_commands_t& p) { core_.on_commands(p); });
  bus_.subscribe<sim_control_t>(channels(Channel::SimControl), [this](const sim_control_t& r) {
    publish(core_.on_control(r, bus_.bad_input().counts()));
  });
}

ServerStats PhysicsServer::stats() const {
  ServerStats s = stats_;
  s.steps = core_.steps();
  s.states_published = core_.states_published();
  s.demand_late = core_.demand_late();
  s.controls_handled = core_.controls_handled();
  s.packets_received = core_.packets_received();
  s.vision_silences = core_.vision_silences();
  return s;
}

int PhysicsServer::run(const ShutdownSignal* shutdown) {
  const World& world = core_.world();
  Pacer& pacer = core_.pacer();
  const auto start = Clock::now();
  const auto geometry_period = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(world.setup().physics.geometry_publish_period));
  publish_geometry();
  // Sync mode, and --wait-for-vision: the first state once the others listen.
  if (!core_.sync() && !options_.wait_for_vision) {
    publish(core_.state());
    first_state_sent_ = true;
  }
  auto next_geometry = start + geometry_period;
  const auto poll_period = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(world.setup().physics.message_poll_period));
  auto next_poll = start;
  pacer.restart(start, world.step_index());
  spdlog::info("physics running: scenario {} on field {} ({:g} x {:g} m), {} robots, {} Hz, {}{}",
               options_.scenario, world.setup().field.name, world.setup().field.field_length,
               world.setup().field.field_width, world.robots().size(), 1.0 / world.dt(),
               core_.sync()                  ? std::string("sync (docs/sync.md)")
               : pacer.lockstep()            ? std::string("lockstep")
               : pacer.as_fast_as_possible() ? std::string("as fast as possible")
                                             : fmt::format("{:g} x real time", pacer.speed()),
               core_.paused() ? ", paused" : "");

  while ((shutdown == nullptr || !shutdown->requested()) && !core_.duration_reached()) {
    auto now = Clock::now();
    if (now >= next_geometry) {
      stepping_clock_.run_ends();
      publish_geometry();
      core_.expire_demand(now);
      if (core_.idle()) publish(core_.state());  // late joiners learn the time while nothing moves
      next_geometry = now + geometry_period;
    }
    if (core_.idle()) {
      wait_until(next_geometry, shutdown);
      continue;
    }
    if (!first_state_sent_) {
      if (core_.ready_to_start()) {
        publish(core_.state());
        first_state_sent_ = true;
        first_state_wall_ = Clock::now();
      } else {
        wait_until(std::min(next_geometry, now + std::chrono::milliseconds(100)), shutdown);
      }
      continue;
    }
    if (core_.sync()) {
      if (!core_.below_horizon()) {
        wait_at_horizon(shutdown);
        continue;
      }
      // Below the horizon: as fast as possible, looking for messages (a
      // further horizon among them) a few thousand times a second.
      if (now >= next_poll) {
        bus_.handle_pending();
        next_poll = now + poll_period;
      }
      if (!core_.idle() && core_.below_horizon() && !core_.duration_reached()) {
        publish(core_.step());
      }
      continue;
    }
    if (pacer.as_fast_as_possible()) {
      // Checking for messages costs system calls; at tens of thousands of
      // steps a second, look a few thousand times a second instead of every step.
      if (now >= next_poll) {
        bus_.handle_pending();
        next_poll = now + poll_period;
      }
      if (core_.waits_for_vision(now)) {
        wait_for_vision(shutdown);
        continue;
      }
      vision_wait_began_.reset();
      if (!core_.idle() && !core_.duration_reached()) publish(core_.step());
      continue;
    }
    const auto due = pacer.due(world.step_index());
    if (now < due) {
      stepping_clock_.run_ends();
      wait_until(std::min(wake_for(due), next_geometry), shutdown);
      continue;
    }
    if (pacer.restart_if_behind(now, world.step_index())) {
      ++stats_.schedule_restarts;
      core_.warnings().warn("pacing",
                            "physics cannot keep up with the requested speed: schedule restarted");
    }
    // Measured only where steps are few (paced), per run of steps.
    stepping_clock_.step_begins();
    const PhysicsCore::Output& out = core_.step();
    if (!out.states.empty()) stepping_clock_.run_ends();  // publishing comes next
    publish(out);
  }
  stepping_clock_.run_ends();
  if (core_.sync() && first_state_sent_ && core_.duration_reached()) {
    wait_for_last_answers(shutdown);
  }
  const auto end = Clock::now();
  stats_.wall_seconds = seconds_between(start, end);
  if (options_.truth_on_demand) {
    spdlog::info(
        "truth on demand: {} states published for {} steps; {} demanded instants came late",
        core_.states_published(), core_.steps(), core_.demand_late());
  }
  stats_.drift =
      pacer.paced() && !core_.paused() && !core_.sync() ? pacer.drift(end, world.step_index()) : 0;
  if ((options_.sync || options_.wait_for_vision) && first_state_sent_) {
    // The start, waiting for the others to listen, left out.
    stats_.sync_run_seconds = seconds_between(first_state_wall_, end);
    spdlog::info("{}: {:.3f} s of sim time in {:.3f} s of wall time from the first state",
                 options_.sync ? "sync" : "as fast as possible", world.time(),
                 stats_.sync_run_seconds);
  }
  if (core_.sync() || !stats_.sync_waits.empty()) log_sync_waits();
  if (stats_.vision_waits > 0 || stats_.vision_silences > 0) {
    spdlog::info(
        "as fast as possible: waited {:.3f} s of wall time for the vision emulator ({} waits, "
        "{} states sent for it); it fell silent {} times",
        stats_.vision_wait_seconds, stats_.vision_waits, stats_.states_for_vision,
        core_.vision_silences());
  }
  if (stepping_clock_.seconds() > 0) {
    spdlog::info("stepping took {:.3f} s of CPU ({:.2f} % of one core over the run)",
                 stepping_clock_.seconds(), 100 * stepping_clock_.seconds() / stats_.wall_seconds);
  }
  spdlog::info("physics stopping: {} steps, {:.3f} s of sim time in {:.3f} s of wall time{}",
               core_.steps(), world.time(), stats_.wall_seconds,
               pacer.paced() && !core_.sync()
                   ? fmt::format(", {:+.1f} ms from the schedule", stats_.drift * 1e3)
                   : std::string());
  return 0;
}

void PhysicsServer::wait_at_horizon(const ShutdownSignal* shutdown) {
  // What is already waiting may move the horizon: no system call to sleep then.
  if (bus_.handle_pending() > 0) return;
  const std::string bound = core_.horizon_bound();
  const auto start = Clock::now();
  wait_until(start + std::chrono::milliseconds(100), shutdown);
  stats_.sync_wait_seconds[bound] += seconds_between(start, Clock::now());
  ++stats_.sync_waits[bound];
}

void PhysicsServer::wait_for_vision(const ShutdownSignal* shutdown) {
  // The step physics waits at: its state goes out (if no demand sent it) for
  // the vision to acknowledge, and again every 100 ms (a vision that started
  // listening after it went out never saw it).
  const auto start = Clock::now();
  constexpr auto kRepeat = std::chrono::milliseconds(100);
  const bool again = vision_wait_began_ && start - *vision_wait_began_ >= kRepeat;
  if (!vision_wait_began_ || again) {
    vision_wait_began_ = start;
    const PhysicsCore::Output& out = core_.state_for_vision(again);
    stats_.states_for_vision += static_cast<std::int64_t>(out.states.size());
    publish(out);
  }
  // What is already waiting may be the acknowledgement: no sleep then.
  if (bus_.handle_pending() > 0) return;
  const auto wait = schedule_wakes_ ? kRepeat : std::chrono::milliseconds(1);
  wait_until(std::min(*vision_wait_began_ + kRepeat, start + wait), shutdown);
  stats_.vision_wait_seconds += seconds_between(start, Clock::now());
  ++stats_.vision_waits;
}

Clock::time_point PhysicsServer::wake_for(Clock::time_point due) const {
  // A command waits in the world until its t_apply whenever it arrived (and
  // is read at the latest when this wait ends), and any other message still
  // wakes physics at once (a new demand may want an earlier state), so only
  // the wall time at which unseen steps run changes. At most
  // 50 ms of steps at once, well within the pacing lag.
  const World& world = core_.world();
  const double window = std::min(0.05, world.setup().physics.max_pacing_lag / 2);
  const auto max_steps = std::max<std::int64_t>(
      1, static_cast<std::int64_t>(window * core_.pacer().speed() / world.dt()));
  const std::int64_t k = core_.steps_to_wanted_state(max_steps);
  return k <= 1 ? due : core_.pacer().due(world.step_index() + k - 1);
}

void PhysicsServer::wait_for_last_answers(const ShutdownSignal* shutdown) {
  // The run ends when physics exits, and the launch script then stops every
  // process: wait until the clients' answers to the frames published up to
  // the last state are in (the radio says so), so that every run's log ends
  // alike. Bounded: a client that never answers is dropped by the radio
  // after its timeout, which also ends this wait.
  const auto deadline = Clock::now() + std::chrono::seconds(3);
  auto stopping = [&] { return shutdown != nullptr && shutdown->requested(); };
  while (!core_.last_frames_answered() && Clock::now() < deadline && !stopping()) {
    if (bus_.handle_pending() > 0) continue;
    wait_until(std::min(deadline, Clock::now() + std::chrono::milliseconds(100)), shutdown);
  }
  if (!core_.last_frames_answered() && !stopping()) {
    spdlog::warn("sync: the run ends without the answers to the last frames (answered until {} s)",
                 core_.answered_until());
  }
}

void PhysicsServer::log_sync_waits() const {
  double total = 0;
  for (const auto& [name, seconds] : stats_.sync_wait_seconds) total += seconds;
  spdlog::info("sync: waited {:.3f} s of wall time at the horizon", total);
  for (const auto& [name, seconds] : stats_.sync_wait_seconds) {
    spdlog::info("sync: waited {:.3f} s for {} ({} waits)", seconds, name,
                 stats_.sync_waits.at(name));
  }
}

void PhysicsServer::wait_until(Clock::time_point deadline, const ShutdownSignal* shutdown) {
  bus_.wait_until_and_handle(deadline, shutdown);
}

void PhysicsServer::publish(const PhysicsCore::Output& out) {
  for (const sim_state_t& state : out.states) {
    // Encoded into a buffer kept across steps (LCM's own publish allocates each time).
    const auto size = static_cast<std::size_t>(state.getEncodedSize());
    if (state_buffer_.size() < size) state_buffer_.resize(size);
    state.encode(state_buffer_.data(), 0, static_cast<int>(size));
    bus_.publish_encoded(state_channel_, state_buffer_.data(), size);
  }
  if (out.geometry) bus_.publish(geometry_channel_, *out.geometry);
  if (out.ack) bus_.publish(ack_channel_, *out.ack);
}

void PhysicsServer::publish_geometry() {
  bus_.publish(geometry_channel_, core_.geometry());
}

}  // namespace ubersim::physics
