#include "ubersim/physics/physics_core.hpp"

#include <cmath>
#include <limits>

namespace ubersim::physics {
namespace {

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
    case sim_control_t::SET_DRIBBLING:
      return "SET_DRIBBLING";
    default:
      return "unknown action";
  }
}

}  // namespace

PhysicsCore::PhysicsCore(WorldSetup setup, CoreOptions options)
    : world_(std::move(setup)),
      options_(std::move(options)),
      speed_(options_.speed < 0 ? -1.0 : options_.speed),
      paused_(options_.paused),
      sync_(options_.sync),
      referee_horizon_(options_.sync_referee ? 0.0 : std::numeric_limits<double>::infinity()) {
  add_own_demand();
}

void PhysicsCore::add_own_demand() {
  // Physics' own consumers in the demand book, beside the programs that ask.
  using While = TruthDemand::While;
  if (!options_.truth_on_demand) demand_.own_every_step(kEveryStepConsumer, While::Always);
  // While no program asks: every step, or STATE_PUBLISH_RATE's instants n /
  // rate, each served by the step nearest to it. In sync mode with the referee
  // every step: the referee judges states a program must otherwise ask for.
  const double rate = world_.setup().physics.state_publish_rate;
  if (rate > 0 && !options_.sync_referee) {
    demand_.own_periodic(kNobodyAsksConsumer, 1.0 / rate, -world_.dt() / 2, While::NobodyAsks);
  } else {
    demand_.own_every_step(kNobodyAsksConsumer, While::NobodyAsks);
  }
}

void PhysicsCore::on_commands(const sim_commands_t& packet) {
  ++packets_received_;
  world_.submit(packet);
}

void PhysicsCore::on_sync_horizon(const sync_horizon_t& h) {
  if (std::isnan(h.horizon)) return;
  horizon_ = h.horizon;
  if (!std::isnan(h.answered_until)) answered_until_ = h.answered_until;
  horizon_heard_ = true;
  horizon_held_by_ = h.held_by;
  horizon_waiting_for_ = h.waiting_for;
}

const PhysicsCore::Output& PhysicsCore::state_to_acknowledge(bool again) {
  clear_output();
  // A reader acknowledges only states it gets: the one physics waits at goes
  // out if no demand sent it. An extra state changes no frame (a capture or
  // release is served by the first state at or after its instant).
  if (again || !(last_state_time_ == world_.time())) add_state();
  return out_;
}

void PhysicsCore::on_referee(const referee_t& r) {
  // The referee has judged the state at r.sim_time and needs none before
  // r.next_judge_time: every step starting before that may go (an older
  // referee that names no later time: just the step from r.sim_time). Game
  // over: the judged state is the last, so every run of a game ends at it.
  const bool ahead = std::isfinite(r.next_judge_time) && r.next_judge_time > r.sim_time;
  referee_horizon_ = r.game_over ? r.sim_time
                     : ahead     ? r.next_judge_time
                                 : r.sim_time + world_.dt() / 2;
  // The state physics waits at for the referee is the referee's demand: it
  // judges that state and names the next one.
  if (options_.sync_referee) demand_.own_from(kRefereeConsumer, referee_horizon_);
}

void PhysicsCore::on_truth_demand(const truth_demand_t& d, Clock::time_point wall) {
  const std::string problem = demand_.on_demand(d, world_.time(), world_.dt(), wall);
  if (!problem.empty()) log_.warn("demand", "ignored a SIM_TRUTH_DEMAND: " + problem);
}

void PhysicsCore::expire_demand(Clock::time_point wall) {
  for (const std::string& gone : demand_.expire(wall, std::chrono::seconds(3))) {
    spdlog::info("truth demand of '{}' forgotten: not heard for 3 s", gone);
  }
}

PhysicsCore::HorizonBound PhysicsCore::horizon_bound() const {
  if (referee_horizon_ < horizon_) return {HorizonBound::By::Referee, {}};
  if (!horizon_heard_) return {};
  if (horizon_held_by_ == sync_horizon_t::HELD_BY_REGISTRATION)
    return {HorizonBound::By::Registration, {}};
  return {HorizonBound::By::Horizon, horizon_waiting_for_};
}

bool PhysicsCore::duration_reached() const {
  return options_.duration > 0 && world_.time() >= options_.duration - world_.dt() / 2;
}

void PhysicsCore::clear_output() {
  for (sim_state_t& s : out_.states) spare_.push_back(std::move(s));
  out_.states.clear();
  out_.geometry.reset();
  out_.ack.reset();
}

const PhysicsCore::Output& PhysicsCore::state() {
  clear_output();
  add_state();
  return out_;
}

const PhysicsCore::Output& PhysicsCore::step() {
  clear_output();
  step_once();
  return out_;
}

void PhysicsCore::step_once() {
  world_.step();
  ++steps_;
  // Only what a consumer wants: ground truth costs only its consumers.
  if (demand_.wanted(world_.time(), world_.dt())) add_state();
}

std::int64_t PhysicsCore::steps_to_wanted_state(std::int64_t max_steps) const {
  const double dt = world_.dt();
  const std::int64_t step = world_.step_index();
  std::int64_t k = 1;
  while (k < max_steps && !demand_.would_want(static_cast<double>(step + k) * dt, dt)) ++k;
  return k;
}

void PhysicsCore::add_state() {
  // Filled into a state of an earlier output, so its arrays keep their memory.
  if (spare_.empty()) {
    out_.states.emplace_back();
  } else {
    out_.states.push_back(std::move(spare_.back()));
    spare_.pop_back();
  }
  sim_state_t& state = out_.states.back();
  world_.fill_state(state);
  state.paused = paused_;
  state.speed_factor = sync_ ? 0.0 : speed_;
  ++states_published_;
  last_state_time_ = world_.time();
  demand_.published(world_.time());
}

void PhysicsCore::acknowledge(const sim_control_t& request, bool ok, const std::string& message) {
  sim_control_ack_t ack{};
  ack.request_id = request.request_id;
  ack.sender = request.sender;
  ack.ok = ok;
  ack.message = message;
  ack.sim_time = world_.time();
  ack.step = world_.step_index();
  out_.ack = ack;
  if (ok) {
    spdlog::debug("{} from '{}' (#{}): {}", action_name(request.action), request.sender,
                  request.request_id, message);
  } else {
    log_.warn("control:" + request.sender, std::string(action_name(request.action)) + " from '" +
                                               request.sender + "' refused: " + message);
  }
}

void PhysicsCore::on_step_request(const sim_control_t& request) {
  const std::int64_t limit = world_.setup().physics.max_steps_per_request;
  if (request.step_count < 1 || request.step_count > limit) {
    acknowledge(request, false,
                "step_count must be 1.." + std::to_string(limit) + ", got " +
                    std::to_string(request.step_count));
    return;
  }
  // Whoever steps by hand sees every state of its steps.
  demand_.own_every_step(kStepRequestConsumer, TruthDemand::While::Always);
  for (int i = 0; i < request.step_count; ++i) step_once();
  demand_.forget(kStepRequestConsumer);
  ++schedule_epoch_;
  acknowledge(request, true, "stepped " + std::to_string(request.step_count));
}

void PhysicsCore::on_speed_request(const sim_control_t& request) {
  if (!std::isfinite(request.speed_factor)) {
    acknowledge(request, false, "speed_factor must be finite");
    return;
  }
  const double speed = request.speed_factor < 0 ? -1.0 : request.speed_factor;
  speed_ = speed;
  ++schedule_epoch_;
  sync_ = false;
  acknowledge(request, true,
              speed < 0    ? std::string("lockstep")
              : speed == 0 ? std::string("as fast as possible")
                           : fmt::format("{:g} x real time", speed));
}

void PhysicsCore::on_define_robot_type(const sim_control_t& request) {
  try {
    world_.define_robot_type(request.robot_type_name, request.robot_type_config);
    acknowledge(request, true, "robot type " + request.robot_type_name + " defined");
  } catch (const std::exception& error) {
    acknowledge(request, false, error.what());
  }
}

void PhysicsCore::on_set_field(const sim_control_t& request) {
  try {
    const std::string done = world_.change_field(request.field_config);
    add_state();
    out_.geometry = world_.geometry();
    acknowledge(request, true, done);
  } catch (const std::exception& error) {
    acknowledge(request, false, error.what());
  }
}

const PhysicsCore::Output& PhysicsCore::on_control(const sim_control_t& request,
                                                   const std::string& dropped_input) {
  ++controls_handled_;
  clear_output();
  switch (request.action) {
    case sim_control_t::PLACE:
    case sim_control_t::SETUP: {
      const PlaceOutcome outcome = world_.place(request, request.action == sim_control_t::SETUP);
      if (outcome.ok) add_state();
      acknowledge(request, outcome.ok, outcome.message);
      return out_;
    }
    case sim_control_t::PAUSE:
      paused_ = true;
      add_state();
      acknowledge(request, true, "paused");
      return out_;
    case sim_control_t::RESUME:
      paused_ = false;
      ++schedule_epoch_;
      acknowledge(request, true, "running");
      return out_;
    case sim_control_t::RESET:
      world_.reset();
      demand_.reset();
      ++schedule_epoch_;
      add_state();
      acknowledge(request, true, "reset to scenario " + options_.scenario);
      return out_;
    case sim_control_t::STEP:
      on_step_request(request);
      return out_;
    case sim_control_t::SET_SPEED:
      on_speed_request(request);
      return out_;
    case sim_control_t::SET_SYNC:
      sync_ = true;
      acknowledge(request, true, "sync");
      return out_;
    case sim_control_t::SET_SEED:
      world_.set_seed(static_cast<std::uint64_t>(request.seed));
      acknowledge(request, true, "seed " + std::to_string(request.seed));
      return out_;
    case sim_control_t::REQUEST_GEOMETRY:
      out_.geometry = world_.geometry();
      acknowledge(request, true, "geometry published");
      return out_;
    case sim_control_t::PING:
      // The status reply: what this process dropped, per kind and channel.
      acknowledge(request, true,
                  "pong; malformed messages dropped: " + dropped_input +
                      "; other warnings (rejected contents, pacing): " + log_.counts() + "; " +
                      command_summary(world_.counters()));
      return out_;
    case sim_control_t::DEFINE_ROBOT_TYPE:
      on_define_robot_type(request);
      return out_;
    case sim_control_t::SET_FIELD:
      on_set_field(request);
      return out_;
    case sim_control_t::SET_DRIBBLING:
      world_.set_perfect_dribbling(request.perfect_dribbling);
      acknowledge(request, true,
                  request.perfect_dribbling ? "perfect dribbling: a dribbler holds the ball"
                                            : "simulated dribbling");
      return out_;
    default:
      acknowledge(request, false, "unknown action " + std::to_string(request.action));
      return out_;
  }
}

}  // namespace ubersim::physics
