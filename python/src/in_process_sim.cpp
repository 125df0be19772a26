#include "in_process_sim.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "ubersim/config_paths.hpp"
#include "ubersim/field_config.hpp"
#include "ubersim/radio/command_validator.hpp"
#include "ubersim/referee/robot_radii.hpp"
#include "ubersim/referee/scene_io.hpp"
#include "ubersim/vision/robot_sizes.hpp"

namespace ubersim::python {
namespace {

physics::WorldSetup load_setup(const SimOptions& options, const std::string& config_dir) {
  physics::WorldSetup setup =
      physics::load_world_setup(config_dir, options.scenario, options.physics);
  if (!options.field.empty()) {
    physics::put_on_field(setup, load_field_config(config_dir, options.field));
  }
  setup.seed = options.seed;
  return setup;
}

physics::CoreOptions core_options(const SimOptions& options) {
  physics::CoreOptions core;
  core.scenario = options.scenario;
  core.speed = 0;  // no wall clock: the caller's steps pace the world
  // Physics steps up to the horizon the radio side names, as under the
  // radio emulator's sync driver (release_until).
  core.sync = true;
  // The emulators see every physics state, as with --truth-every-step.
  core.truth_on_demand = false;
  return core;
}

sim_control_t control_request(std::int32_t action) {
  sim_control_t request{};
  request.action = action;
  request.sender = "python";
  return request;
}

// The entries of one team's orders, in row order, as its software would send them.
radio_packet_t team_packet(Team team, const std::vector<RobotOrder>& orders) {
  radio_packet_t packet{};
  packet.team = static_cast<std::int8_t>(team);
  for (const RobotOrder& order : orders) {
    if (order.team != team) continue;
    packet.commands.push_back(order.command);
    packet.commands.back().robot_id = order.id;
  }
  packet.num_commands = static_cast<std::int32_t>(packet.commands.size());
  return packet;
}

radio::RobotsOnField robots_on_field(const physics::World& world, Team team) {
  radio::RobotsOnField robots;
  for (const auto& robot : world.robots()) {
    if (robot->team() != team) continue;
    robots[robot->id()] = static_cast<std::int32_t>(robot->type().wheel_count());
  }
  return robots;
}

// The row a finding is about: a robot's first row, its second when commanded twice.
std::size_t finding_row(const std::vector<RobotOrder>& orders, Team team,
                        const radio::Finding& finding) {
  int wanted = finding.problem == radio::Problem::DuplicateRobot ? 2 : 1;
  for (std::size_t row = 0; row < orders.size(); ++row) {
    if (orders[row].team == team && orders[row].id == finding.robot_id && --wanted == 0) {
      return row;
    }
  }
  return orders.size();
}

std::string finding_text(const radio::Finding& finding) {
  return finding.problem == radio::Problem::DuplicateRobot ? "robot commanded twice in one step"
                                                           : finding.detail;
}

}  // namespace

InProcessSim::InProcessSim(SimOptions options)
    : options_(std::move(options)),
      config_dir_(options_.config_dir.empty() ? default_config_dir().string()
                                              : options_.config_dir) {
  if (!(options_.step > 0) || !std::isfinite(options_.step)) {
    throw std::invalid_argument("step must be a positive number of seconds, got " +
                                std::to_string(options_.step));
  }
  physics::WorldSetup setup = load_setup(options_, config_dir_);
  if (!setup.robots.empty()) default_robot_type_ = setup.robots.front().type;
  // Every step's state goes to the emulators, whatever rate the config sets
  // for the physics process's SIM_STATE.
  setup.physics.state_publish_rate = 0;
  core_ = std::make_unique<physics::PhysicsCore>(std::move(setup), core_options(options_));
  const double dt = core_->world().dt();
  if (options_.step < dt * 0.5) {
    throw std::invalid_argument("step must be at least half a physics step (" + std::to_string(dt) +
                                " s)");
  }
  start_emulators();
}

void InProcessSim::start_emulators() {
  vision_.reset();
  radio_.reset();
  if (!options_.vision_profile.empty()) {
    vision::VisionProfile profile =
        vision::load_vision_profile(config_dir_, options_.vision_profile);
    profile.seed = options_.seed;
    vision_ = std::make_unique<vision::VisionEmulator>(
        profile, vision::RobotSizes::from_config_dir(config_dir_));
    vision_->on_field_geometry(core_->geometry());
  }
  if (!options_.radio_profile.empty()) {
    const radio::RadioProfile profile =
        radio::load_radio_profile(config_dir_, options_.radio_profile);
    radio_ = std::make_unique<radio::RadioEmulator>(
        std::array<radio::RadioProfile, 2>{profile, profile}, options_.seed);
    // Sync mode: a packet arrives at the sim time given, and a waiting packet
    // leaves when no newer one can come first; no wall clock is involved.
    radio_->set_sync(true);
  }
  steps_taken_ = 0;
  // The state at sim time 0: vision's first capture, the radio's clock and
  // the robots it may command.
  if (vision_ || radio_) feed_emulators(core_->state().states);
  out_.frames.clear();
  out_.feedback.clear();
}

void InProcessSim::control(const sim_control_t& request) {
  const physics::PhysicsCore::Output& out = core_->on_control(request, "");
  if (out.ack && !out.ack->ok) throw std::invalid_argument(out.ack->message);
}

void InProcessSim::reset(std::optional<std::uint64_t> seed) {
  if (seed) {
    options_.seed = *seed;
    sim_control_t request = control_request(sim_control_t::SET_SEED);
    request.seed = static_cast<std::int64_t>(*seed);
    control(request);
  }
  control(control_request(sim_control_t::RESET));
  start_emulators();
}

void InProcessSim::place(const sim_control_t& request, bool setup) {
  sim_control_t placement = request;
  placement.action = setup ? sim_control_t::SETUP : sim_control_t::PLACE;
  placement.sender = "python";
  control(placement);
}

void InProcessSim::situation(const referee::SituationRequest& request, referee::FieldSides sides) {
  const field_geometry_t field = core_->geometry();
  referee::RobotRadii radii(config_dir_);
  const referee::PlacementScene before = referee::scene_from_state(
      truth(), field.ball_radius, [&radii](const std::string& type) { return radii(type); });
  referee::PlacementScene planned;
  try {
    planned = referee::plan_situation(request, before, field, sides);
  } catch (const std::runtime_error& error) {
    throw std::invalid_argument(error.what());
  }
  place(referee::place_request(before, planned, true, true), false);
}

void InProcessSim::check_orders(const std::vector<RobotOrder>& orders) const {
  // The radio emulator's validator, without the profile's sanity limits: an
  // emulated radio applies those (dropping and counting), else physics clamps.
  std::size_t first_row = orders.size();
  std::string problem;
  for (Team team : kTeams) {
    const radio_packet_t packet = team_packet(team, orders);
    if (packet.commands.empty()) continue;
    const radio::Validated validated =
        radio::validate_packet(packet, team, robots_on_field(core_->world(), team));
    for (const radio::Finding& finding : validated.findings) {
      const std::size_t row = finding_row(orders, team, finding);
      if (row >= first_row) continue;
      first_row = row;
      problem = "commands row " + std::to_string(row) + " (" + robot_name(team, finding.robot_id) +
                "): " + finding_text(finding);
    }
  }
  if (!problem.empty()) throw std::invalid_argument(problem);
}

std::optional<std::size_t> InProcessSim::wheel_count(Team team, int id) const {
  const physics::Robot* robot = core_->world().robot(team, id);
  if (robot == nullptr) return std::nullopt;
  return robot->type().wheel_count();
}

void InProcessSim::send(const std::vector<RobotOrder>& orders) {
  const double now = core_->world().time();
  for (Team team : kTeams) {
    radio_packet_t packet = team_packet(team, orders);
    if (packet.commands.empty()) continue;  // this team sends nothing this step
    packet.sequence = ++packet_sequence_;
    packet.t_sent = now;
    if (radio_) {
      for (const sim_commands_t& c : radio_->on_answer(team, packet, now).commands) {
        core_->on_commands(c);
      }
      continue;
    }
    // No radio: the commands reach the robots at once, as SIM_COMMANDS
    // applied at the step starting now.
    sim_commands_t direct{};
    direct.team = packet.team;
    direct.sequence = packet.sequence;
    direct.t_received = now;
    direct.t_apply = now;
    direct.commands = std::move(packet.commands);
    direct.num_commands = packet.num_commands;
    core_->on_commands(direct);
  }
}

void InProcessSim::release_until(double end) {
  sync_horizon_t horizon{};
  horizon.horizon = end;  // without a radio: the caller's next commands apply at `end`
  horizon.answered_until = end;
  horizon.held_by = sync_horizon_t::HELD_BY_CLIENT;
  if (radio_) {
    // What the links transmit before the caller's next packet goes out now,
    // to be applied at its own t_apply during the steps; physics may step up
    // to the earliest t_apply still possible (at or after `end`).
    horizon.horizon = std::numeric_limits<double>::infinity();
    for (Team team : kTeams) {
      radio::RadioEmulator::SyncRelease release = radio_->sync_release(team, end);
      for (const sim_commands_t& c : release.out.commands) core_->on_commands(c);
      horizon.horizon = std::min(horizon.horizon, release.horizon);
    }
  }
  core_->on_sync_horizon(horizon);
}

void InProcessSim::feed_emulators(const std::vector<sim_state_t>& states) {
  for (const sim_state_t& state : states) {
    if (vision_) {
      auto frames = vision_->on_sim_state(state).frames;
      for (auto& frame : frames) out_.frames.push_back(std::move(frame));
    }
    if (radio_) {
      // Speed 0 and sync mode: no wall time enters the radio (any instant will do).
      radio::RadioEmulator::Output radio_out =
          radio_->on_sim_state(state, radio::RadioEmulator::Clock::time_point{});
      for (auto& feedback : radio_out.feedback) out_.feedback.push_back(std::move(feedback));
    }
  }
}

const StepOutput& InProcessSim::step(const std::vector<RobotOrder>& orders) {
  out_.frames.clear();
  out_.feedback.clear();
  send(orders);
  ++steps_taken_;
  const double end = static_cast<double>(steps_taken_) * options_.step;
  release_until(end);
  const physics::World& world = core_->world();
  while (world.time() < end - world.dt() / 2 && core_->below_horizon()) {
    feed_emulators(core_->step().states);
  }
  world.fill_state(out_.truth);
  return out_;
}

const sim_state_t& InProcessSim::truth() {
  core_->world().fill_state(out_.truth);
  return out_.truth;
}

}  // namespace ubersim::python
