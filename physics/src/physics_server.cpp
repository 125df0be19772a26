#include "ubersim/physics/physics_server.hpp"

#include <cmath>
#include <limits>
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

const char* action_name(int action) {
  switch (action) {
    case sim_control_t::PLACE:
      return "PLACE";
    case sim_control_t::SETUP:
      return "SETUP";
    case sim_control_t::PAUSE:
      return "PAUSE";
    case sim_control_t::RESUME:
      return "RESUME";
    case sim_control_t::RESET:
      return "RESET";
    case sim_control_t::STEP:
      return "STEP";
    case sim_control_t::SET_SPEED:
      return "SET_SPEED";
    case sim_control_t::SET_SEED:
      return "SET_SEED";
    case sim_control_t::REQUEST_GEOMETRY:
      return "REQUEST_GEOMETRY";
    case sim_control_t::DEFINE_ROBOT_TYPE:
      return "DEFINE_ROBOT_TYPE";
    case sim_control_t::SET_FIELD:
      return "SET_FIELD";
    case sim_control_t::PING:
      return "PING";
    case sim_control_t::SET_SYNC:
      return "SET_SYNC";
    default:
      return "unknown action";
  }
}

}  // namespace

PhysicsServer::PhysicsServer(WorldSetup setup, MessageBus& bus, const ChannelNames& channels,
                             ServerOptions options)
    : world_(std::move(setup)),
      bus_(bus),
      state_channel_(channels(Channel::SimState)),
      geometry_channel_(channels(Channel::SimGeometry)),
      ack_channel_(channels(Channel::SimControlAck)),
      options_(std::move(options)),
      pacer_(world_.dt(), options_.speed < 0 ? -1.0 : options_.speed,
             world_.setup().physics.max_pacing_lag),
      paused_(options_.paused),
      next_state_time_(first_state_time()),
      sync_(options_.sync),
      referee_horizon_(options_.sync_referee ? 0.0 : std::numeric_limits<double>::infinity()) {
  if (options_.sync_referee) {
    // The referee has judged the state at r.sim_time: the step starting there may go.
    bus_.subscribe<referee_t>(channels.referee(), [this](const referee_t& r) {
      referee_horizon_ =
          r.game_over ? std::numeric_limits<double>::infinity() : r.sim_time + world_.dt() / 2;
    });
  }
  bus_.subscribe<sync_horizon_t>(channels.extra(kSyncHorizonChannel),
                                 [this](const sync_horizon_t& h) {
                                   if (std::isnan(h.horizon)) return;
                                   horizon_ = h.horizon;
                                   // Until its clients registered, the radio holds the start.
                                   radio_ready_ = h.waiting_for != "registration";
                                   horizon_bound_ = h.waiting_for.empty() ? "?" : h.waiting_for;
                                 });
  if (options_.truth_on_demand) {
    bus_.subscribe<truth_demand_t>(
        channels.extra(kTruthDemandChannel), [this](const truth_demand_t& d) {
          const std::string problem =
              demand_.on_demand(d, world_.time(), world_.dt(), Clock::now());
          if (!problem.empty()) log_.warn("demand", "ignored a SIM_TRUTH_DEMAND: " + problem);
        });
  }
  bus_.subscribe<vision_schedule_t>(channels.extra(kVisionScheduleChannel),
                                    [this](const vision_schedule_t&) { vision_heard_ = true; });
  bus_.subscribe<sim_commands_t>(channels(Channel::SimCommands), [this](const sim_commands_t& p) {
    ++stats_.packets_received;
    world_.submit(p);
  });
  bus_.subscribe<sim_control_t>(channels(Channel::SimControl),
                                [this](const sim_control_t& r) { on_control(r); });
}

bool PhysicsServer::duration_reached() const {
  return options_.duration > 0 && world_.time() >= options_.duration - world_.dt() / 2;
}

int PhysicsServer::run(const ShutdownSignal* shutdown) {
  const auto start = Clock::now();
  const auto geometry_period = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(world_.setup().physics.geometry_publish_period));
  publish_geometry();
  if (!sync_) {
    publish_state();
    first_state_sent_ = true;
  }
  auto next_geometry = start + geometry_period;
  const auto poll_period = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(world_.setup().physics.message_poll_period));
  auto next_poll = start;
  pacer_.restart(start, world_.step_index());
  spdlog::info("physics running: scenario {}, {} robots, {} Hz, {}{}", options_.scenario,
               world_.robots().size(), 1.0 / world_.dt(),
               sync_                          ? std::string("sync (docs/sync.md)")
               : pacer_.lockstep()            ? std::string("lockstep")
               : pacer_.as_fast_as_possible() ? std::string("as fast as possible")
                                              : fmt::format("{:g} x real time", pacer_.speed()),
               paused_ ? ", paused" : "");

  while ((shutdown == nullptr || !shutdown->requested()) && !duration_reached()) {
    auto now = Clock::now();
    if (now >= next_geometry) {
      publish_geometry();
      for (const std::string& gone : demand_.expire(now, std::chrono::seconds(3))) {
        spdlog::info("truth demand of '{}' forgotten: not heard for 3 s", gone);
      }
      if (idle()) publish_state();  // late joiners learn the time while nothing moves
      next_geometry = now + geometry_period;
    }
    if (idle()) {
      wait_until(next_geometry, shutdown);
      continue;
    }
    if (sync_ && !first_state_sent_) {
      if (vision_heard_ && radio_ready_) {
        publish_state();
        first_state_sent_ = true;
        first_state_wall_ = Clock::now();
      } else {
        wait_until(std::min(next_geometry, now + std::chrono::milliseconds(100)), shutdown);
      }
      continue;
    }
    if (sync_) {
      if (!below_horizon()) {
        wait_at_horizon(shutdown);
        continue;
      }
      // Below the horizon: as fast as possible, looking for messages (a
      // further horizon among them) a few thousand times a second.
      if (now >= next_poll) {
        bus_.handle_pending();
        next_poll = now + poll_period;
      }
      if (!idle() && below_horizon() && !duration_reached()) step_and_publish(false);
      continue;
    }
    if (pacer_.as_fast_as_possible()) {
      // Checking for messages costs system calls; at tens of thousands of
      // steps a second, look a few thousand times a second instead of every step.
      if (now >= next_poll) {
        bus_.handle_pending();
        next_poll = now + poll_period;
      }
      if (!idle() && !duration_reached()) step_and_publish(false);
      continue;
    }
    const auto due = pacer_.due(world_.step_index());
    if (now < due) {
      wait_until(std::min(due, next_geometry), shutdown);
      continue;
    }
    if (pacer_.restart_if_behind(now, world_.step_index())) {
      ++stats_.schedule_restarts;
      log_.warn("pacing", "physics cannot keep up with the requested speed: schedule restarted");
    }
    step_and_publish(false);
  }
  const auto end = Clock::now();
  stats_.wall_seconds = seconds_between(start, end);
  stats_.demand_late = demand_.late();
  if (options_.truth_on_demand) {
    spdlog::info(
        "truth on demand: {} states published for {} steps; {} demanded instants came late",
        stats_.states_published, stats_.steps, demand_.late());
  }
  stats_.drift = pacer_.paced() && !paused_ && !sync_ ? pacer_.drift(end, world_.step_index()) : 0;
  if (options_.sync && first_state_sent_) {
    stats_.sync_run_seconds = seconds_between(first_state_wall_, end);
    spdlog::info("sync: {:.3f} s of sim time in {:.3f} s of wall time from the first state",
                 world_.time(), stats_.sync_run_seconds);
  }
  if (sync_ || !stats_.sync_waits.empty()) log_sync_waits();
  spdlog::info("physics stopping: {} steps, {:.3f} s of sim time in {:.3f} s of wall time{}",
               stats_.steps, world_.time(), stats_.wall_seconds,
               pacer_.paced() && !sync_
                   ? fmt::format(", {:+.1f} ms from the schedule", stats_.drift * 1e3)
                   : std::string());
  return 0;
}

void PhysicsServer::wait_at_horizon(const ShutdownSignal* shutdown) {
  // What is already waiting may move the horizon: no system call to sleep then.
  if (bus_.handle_pending() > 0) return;
  const std::string bound = referee_horizon_ < horizon_ ? "referee" : horizon_bound_;
  const auto start = Clock::now();
  wait_until(start + std::chrono::milliseconds(100), shutdown);
  stats_.sync_wait_seconds[bound] += seconds_between(start, Clock::now());
  ++stats_.sync_waits[bound];
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

double PhysicsServer::first_state_time() const {
  // Step 0 is published at start (and after a reset); then one per 1 / rate.
  const double rate = world_.setup().physics.state_publish_rate;
  return rate > 0 ? 1.0 / rate : 0.0;
}

void PhysicsServer::step_and_publish(bool publish_every_step) {
  world_.step();
  ++stats_.steps;
  const double rate = world_.setup().physics.state_publish_rate;
  if (options_.truth_on_demand && !publish_every_step && !options_.sync_referee &&
      !demand_.empty()) {
    // Only what someone asked for: ground truth costs only its consumers.
    if (demand_.wanted(world_.time(), world_.dt())) publish_state();
    return;
  }
  if (publish_every_step || rate <= 0 || options_.sync_referee) {
    publish_state();
  } else if (world_.time() >= next_state_time_ - world_.dt() / 2) {
    publish_state();
    next_state_time_ += 1.0 / rate;
    if (next_state_time_ < world_.time()) next_state_time_ = world_.time() + 1.0 / rate;
  }
}

void PhysicsServer::publish_state() {
  world_.fill_state(state_);
  state_.paused = paused_;
  state_.speed_factor = sync_ ? 0.0 : pacer_.speed();
  // Encoded into a buffer kept across steps (LCM's own publish allocates each time).
  const auto size = static_cast<std::size_t>(state_.getEncodedSize());
  if (state_buffer_.size() < size) state_buffer_.resize(size);
  state_.encode(state_buffer_.data(), 0, static_cast<int>(size));
  bus_.publish_encoded(state_channel_, state_buffer_.data(), size);
  ++stats_.states_published;
  demand_.published(world_.time());
}

void PhysicsServer::publish_geometry() {
  bus_.publish(geometry_channel_, world_.geometry());
}

void PhysicsServer::acknowledge(const sim_control_t& request, bool ok, const std::string& message) {
  sim_control_ack_t ack{};
  ack.request_id = request.request_id;
  ack.sender = request.sender;
  ack.ok = ok;
  ack.message = message;
  ack.sim_time = world_.time();
  ack.step = world_.step_index();
  bus_.publish(ack_channel_, ack);
  if (ok) {
    spdlog::debug("{} from '{}' (#{}): {}", action_name(request.action), request.sender,
                  request.request_id, message);
  } else {
    log_.warn("control:" + request.sender, std::string(action_name(request.action)) + " from '" +
                                               request.sender + "' refused: " + message);
  }
}

void PhysicsServer::on_control(const sim_control_t& request) {
  ++stats_.controls_handled;
  const auto now = Clock::now();
  switch (request.action) {
    case sim_control_t::PLACE:
    case sim_control_t::SETUP: {
      const PlaceOutcome outcome = world_.place(request, request.action == sim_control_t::SETUP);
      if (outcome.ok) publish_state();
      acknowledge(request, outcome.ok, outcome.message);
      return;
    }
    case sim_control_t::PAUSE:
      paused_ = true;
      publish_state();
      acknowledge(request, true, "paused");
      return;
    case sim_control_t::RESUME:
      paused_ = false;
      pacer_.restart(now, world_.step_index());
      acknowledge(request, true, "running");
      return;
    case sim_control_t::RESET:
      world_.reset();
      demand_.reset();
      next_state_time_ = first_state_time();
      pacer_.restart(now, world_.step_index());
      publish_state();
      acknowledge(request, true, "reset to scenario " + options_.scenario);
      return;
    case sim_control_t::STEP: {
      const std::int64_t limit = world_.setup().physics.max_steps_per_request;
      if (request.step_count < 1 || request.step_count > limit) {
        acknowledge(request, false,
                    "step_count must be 1.." + std::to_string(limit) + ", got " +
                        std::to_string(request.step_count));
        return;
      }
      for (int i = 0; i < request.step_count; ++i) step_and_publish(true);
      pacer_.restart(Clock::now(), world_.step_index());
      acknowledge(request, true, "stepped " + std::to_string(request.step_count));
      return;
    }
    case sim_control_t::SET_SPEED: {
      if (!std::isfinite(request.speed_factor)) {
        acknowledge(request, false, "speed_factor must be finite");
        return;
      }
      const double speed = request.speed_factor < 0 ? -1.0 : request.speed_factor;
      pacer_.set_speed(speed, now, world_.step_index());
      sync_ = false;
      acknowledge(request, true,
                  speed < 0    ? std::string("lockstep")
                  : speed == 0 ? std::string("as fast as possible")
                               : fmt::format("{:g} x real time", speed));
      return;
    }
    case sim_control_t::SET_SYNC:
      sync_ = true;
      acknowledge(request, true, "sync");
      return;
    case sim_control_t::SET_SEED:
      world_.set_seed(static_cast<std::uint64_t>(request.seed));
      acknowledge(request, true, "seed " + std::to_string(request.seed));
      return;
    case sim_control_t::REQUEST_GEOMETRY:
      publish_geometry();
      acknowledge(request, true, "geometry published");
      return;
    case sim_control_t::PING:
      // The status reply: what this process dropped, per kind and channel.
      acknowledge(request, true,
                  "pong; malformed messages dropped: " + bus_.bad_input().counts() +
                      "; other warnings (rejected contents, pacing): " + log_.counts());
      return;
    case sim_control_t::DEFINE_ROBOT_TYPE:
      try {
        world_.define_robot_type(request.robot_type_name, request.robot_type_config);
        acknowledge(request, true, "robot type " + request.robot_type_name + " defined");
      } catch (const std::exception& error) {
        acknowledge(request, false, error.what());
      }
      return;
    case sim_control_t::SET_FIELD:
      try {
        const std::string done = world_.change_field(request.field_config);
        publish_state();
        publish_geometry();
        acknowledge(request, true, done);
      } catch (const std::exception& error) {
        acknowledge(request, false, error.what());
      }
      return;
    default:
      acknowledge(request, false, "unknown action " + std::to_string(request.action));
      return;
  }
}

}  // namespace ubersim::physics
