#include "in_process_sim.hpp"

#include <cmath>
#include <set>
#include <stdexcept>

#include "ubersim/config_paths.hpp"
#include "ubersim/field_config.hpp"
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

bool finite_command(const robot_command_t& c) {
  for (double v :
       {c.vx, c.vy, c.omega, c.kick_speed, c.chip_speed, c.chip_angle, c.dribbler_speed}) {
    if (!std::isfinite(v)) return false;
  }
  for (double w : c.wheel_speeds) {
    if (!std::isfinite(w)) return false;
  }
  return true;
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
  world_ = std::make_unique<physics::World>(std::move(setup));
  if (options_.step < world_->dt() * 0.5) {
    throw std::invalid_argument("step must be at least half a physics step (" +
                                std::to_string(world_->dt()) + " s)");
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
    vision_->on_field_geometry(world_->geometry());
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
  out_.frames.clear();
  out_.feedback.clear();
  // The state at sim time 0: vision's first capture, the radio's clock and
  // the robots it may command.
  feed_emulators();
  out_.frames.clear();
  out_.feedback.clear();
}

void InProcessSim::reset(std::optional<std::uint64_t> seed) {
  if (seed) {
    options_.seed = *seed;
    world_->set_seed(*seed);
  }
  world_->reset();
  start_emulators();
}

void InProcessSim::place(const sim_control_t& request, bool setup) {
  const physics::PlaceOutcome outcome = world_->place(request, setup);
  if (!outcome.ok) throw std::invalid_argument(outcome.message);
}

void InProcessSim::situation(const referee::SituationRequest& request, referee::FieldSides sides) {
  const field_geometry_t field = world_->geometry();
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
  std::set<std::pair<int, int>> seen;
  for (std::size_t row = 0; row < orders.size(); ++row) {
    const RobotOrder& order = orders[row];
    const std::string where =
        "commands row " + std::to_string(row) + " (" + robot_name(order.team, order.id) + "): ";
    const physics::Robot* robot = world_->robot(order.team, order.id);
    if (robot == nullptr) throw std::invalid_argument(where + "no such robot on the field");
    if (!seen.insert({static_cast<int>(order.team), order.id}).second) {
      throw std::invalid_argument(where + "robot commanded twice in one step");
    }
    const robot_command_t& c = order.command;
    if (!finite_command(c)) throw std::invalid_argument(where + "a value is NaN or infinite");
    if (c.mode < robot_command_t::MODE_LOCAL_VELOCITY ||
        c.mode > robot_command_t::MODE_WHEEL_SPEEDS) {
      throw std::invalid_argument(where +
                                  "mode must be 0 (local velocity), 1 (global velocity) or "
                                  "2 (wheel speeds), got " +
                                  std::to_string(int{c.mode}));
    }
    if (c.mode == robot_command_t::MODE_WHEEL_SPEEDS &&
        static_cast<std::size_t>(c.num_wheels) != robot->type().wheel_count()) {
      throw std::invalid_argument(where + "the robot has " +
                                  std::to_string(robot->type().wheel_count()) + " wheels, got " +
                                  std::to_string(c.num_wheels) + " wheel speeds");
    }
  }
}

std::optional<std::size_t> InProcessSim::wheel_count(Team team, int id) const {
  const physics::Robot* robot = world_->robot(team, id);
  if (robot == nullptr) return std::nullopt;
  return robot->type().wheel_count();
}

void InProcessSim::send(const std::vector<RobotOrder>& orders) {
  if (!radio_) {
    for (const RobotOrder& order : orders) world_->command(order.team, order.id, order.command);
    return;
  }
  const double now = world_->time();
  for (Team team : kTeams) {
    radio_packet_t packet{};
    packet.team = static_cast<std::int8_t>(team);
    packet.sequence = ++packet_sequence_;
    packet.t_sent = now;
    for (const RobotOrder& order : orders) {
      if (order.team != team) continue;
      packet.commands.push_back(order.command);
      packet.commands.back().robot_id = order.id;
    }
    if (packet.commands.empty()) continue;  // this team sends nothing this step
    packet.num_commands = static_cast<std::int32_t>(packet.commands.size());
    for (const sim_commands_t& c : radio_->on_answer(team, packet, now).commands) world_->submit(c);
  }
}

void InProcessSim::feed_emulators() {
  if (!vision_ && !radio_) return;
  world_->fill_state(state_);
  state_.paused = false;
  state_.speed_factor = 0;
  if (vision_) {
    auto frames = vision_->on_sim_state(state_).frames;
    for (auto& frame : frames) out_.frames.push_back(std::move(frame));
  }
  if (radio_) {
    // Speed 0 and sync mode: no wall time enters the radio (any instant will do).
    radio::RadioEmulator::Output radio_out =
        radio_->on_sim_state(state_, radio::RadioEmulator::Clock::time_point{});
    for (auto& feedback : radio_out.feedback) out_.feedback.push_back(std::move(feedback));
  }
}

const StepOutput& InProcessSim::step(const std::vector<RobotOrder>& orders) {
  out_.frames.clear();
  out_.feedback.clear();
  send(orders);
  ++steps_taken_;
  const double end = static_cast<double>(steps_taken_) * options_.step;
  if (radio_) {
    // The caller's next packet arrives at the end of this step at the
    // earliest: what the links transmit before then goes out now, to be
    // applied at its own t_apply during the steps below.
    for (Team team : kTeams) {
      for (const sim_commands_t& c : radio_->sync_poll(team, end).commands) world_->submit(c);
    }
  }
  const double dt = world_->dt();
  while (world_->time() < end - dt / 2) {
    world_->step();
    feed_emulators();
  }
  world_->fill_state(out_.truth);
  return out_;
}

const sim_state_t& InProcessSim::truth() {
  world_->fill_state(out_.truth);
  return out_.truth;
}

}  // namespace ubersim::python
