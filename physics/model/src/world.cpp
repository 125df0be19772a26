#include "ubersim/physics/world.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>

#include "ubersim/config_paths.hpp"
#include "ubersim/scenario_config.hpp"

namespace ubersim::physics {

RobotTypeSource robot_types_from(const std::string& config_dir) {
  struct Cache {
    std::mutex mutex;
    std::map<std::string, std::shared_ptr<const RobotTypeConfig>> types;
  };
  auto cache = std::make_shared<Cache>();
  return [cache, config_dir](const std::string& name) {
    std::lock_guard<std::mutex> lock(cache->mutex);
    auto found = cache->types.find(name);
    if (found != cache->types.end()) return found->second;
    auto type = std::make_shared<const RobotTypeConfig>(load_robot_config(config_dir, name));
    cache->types.emplace(name, type);
    return std::shared_ptr<const RobotTypeConfig>(type);
  };
}

WorldSetup load_world_setup(const std::string& config_dir, const std::string& scenario,
                            const std::string& physics_config) {
  const ScenarioConfig s = load_scenario_config(config_dir, scenario);
  WorldSetup setup;
  setup.field = load_field_config(config_dir, s.field);
  setup.ball = load_ball_config(config_dir, s.ball);
  setup.physics = load_physics_config(config_dir, physics_config);
  setup.ball_x = s.ball_x;
  setup.ball_y = s.ball_y;
  setup.robot_types = robot_types_from(config_dir);
  for (const auto& r : s.robots) {
    RobotSpawn spawn;
    spawn.team = r.team;
    spawn.id = r.id;
    spawn.type = r.type;
    spawn.state.x = r.x;
    spawn.state.y = r.y;
    spawn.state.heading = r.orientation;
    setup.robots.push_back(spawn);
    setup.robot_types(r.type);  // fail now, naming the file, not at the first step
  }
  return setup;
}

void put_on_field(WorldSetup& setup, const FieldConfig& field) {
  const double sx = field.field_length / setup.field.field_length;
  const double sy = field.field_width / setup.field.field_width;
  for (RobotSpawn& spawn : setup.robots) {
    spawn.state.x *= sx;
    spawn.state.y *= sy;
  }
  setup.ball_x *= sx;
  setup.ball_y *= sy;
  setup.field = field;
}

World::World(WorldSetup setup) : setup_(std::move(setup)), dt_(setup_.physics.dt()) {
  ensure_ode_initialised();
  ball_surface_ = derive_ball_surface(setup_.ball, setup_.physics.gravity);
  build();
}

World::~World() = default;

void World::build() {
  const PhysicsConfig& p = setup_.physics;
  robots_.clear();
  ball_.reset();
  field_.reset();
  contact_handler_.reset();
  contacts_.reset();
  space_.reset();
  if (!threading_) threading_.reset(dThreadingAllocateSelfThreadedImplementation());
  world_.reset(dWorldCreate());
  dWorldID w = world_.get();
  dWorldSetStepThreadingImplementation(w, dThreadingImplementationGetFunctions(threading_.get()),
                                       threading_.get());
  dWorldSetGravity(w, 0, 0, -p.gravity);
  dWorldSetERP(w, p.erp);
  dWorldSetCFM(w, p.cfm);
  dWorldSetQuickStepNumIterations(w, p.solver_iterations);
  dWorldSetQuickStepW(w, p.solver_sor);
  dWorldSetContactMaxCorrectingVel(w, p.contact_max_correcting_velocity);
  dWorldSetContactSurfaceLayer(w, p.contact_surface_layer);
  dWorldSetAutoDisableFlag(w, 0);
  space_ = make_simple_space(nullptr);
  contacts_.reset(dJointGroupCreate(0));
  field_ = build_field(setup_.field, space_.get());
  ball_ = std::make_unique<Ball>(w, space_.get(), setup_.ball, ball_surface_);
  contact_handler_ =
      std::make_unique<ContactHandler>(setup_.physics, setup_.field, setup_.ball, ball_surface_);
  place_ball(setup_.ball_x, setup_.ball_y, 0, 0, 0, 0);
  for (const RobotSpawn& spawn : setup_.robots)
    add_robot(spawn.team, spawn.id, spawn.type, spawn.state);
  step_ = 0;
  solver_random_state_ = static_cast<unsigned long>(setup_.seed);
  for (auto& line : pending_) line.clear();
  ball_force_.reset();
  robot_force_.clear();
}

void World::reset() {
  build();
}

void World::set_seed(std::uint64_t seed) {
  setup_.seed = seed;
  solver_random_state_ = static_cast<unsigned long>(seed);
}

Robot& World::add_robot(Team team, int id, const std::string& type, const PlanarState& state) {
  remove_robot(team, id);
  auto robot = std::make_unique<Robot>(world_.get(), space_.get(), setup_.physics, setup_.ball,
                                       setup_.robot_types(type), team, id);
  robot->place(state);
  robot->remember_good_state();
  const auto key = std::make_pair(static_cast<int>(team), id);
  auto at = std::lower_bound(robots_.begin(), robots_.end(), key, [](const auto& r, const auto& k) {
    return std::make_pair(static_cast<int>(r->team()), r->id()) < k;
  });
  return **robots_.insert(at, std::move(robot));
}

bool World::remove_robot(Team team, int id) {
  auto found = std::find_if(robots_.begin(), robots_.end(),
                            [&](const auto& r) { return r->team() == team && r->id() == id; });
  if (found == robots_.end()) return false;
  robots_.erase(found);
  robot_force_.erase({static_cast<int>(team), id});
  return true;
}

Robot* World::robot(Team team, int id) {
  for (auto& r : robots_) {
    if (r->team() == team && r->id() == id) return r.get();
  }
  return nullptr;
}

void World::set_perfect_dribbling(bool perfect) {
  perfect_dribbling_ = perfect;
  if (!perfect) {
    for (auto& r : robots_) r->release_ball();
  }
}

void World::place_ball(double x, double y, double z, double vx, double vy, double vz) {
  for (auto& r : robots_) r->release_ball();  // a placed ball is free
  const double r = setup_.ball.radius;
  const double position[3] = {x, y, std::max(z, r)};
  const double velocity[3] = {vx, vy, vz};
  ball_->place(position, velocity);
  ball_last_good_ = {position[0], position[1], position[2]};
}

void World::submit(const sim_commands_t& packet) {
  if (packet.team != 0 && packet.team != 1) {
    ++counters_.packets_dropped;
    log_.warn("packet:team",
              "dropped a SIM_COMMANDS packet for unknown team " + std::to_string(packet.team));
    return;
  }
  if (!std::isfinite(packet.t_apply) || !std::isfinite(packet.command_timeout)) {
    ++counters_.packets_dropped;
    log_.warn("packet:time", "dropped a SIM_COMMANDS packet with a non-finite time");
    return;
  }
  pending_[packet.team == 0 ? 0 : 1].push(packet.t_apply, packet);
}

void World::apply_due_commands() {
  // A packet due at t is applied at the first step starting at or after t;
  // the tolerance absorbs rounding of t = step * dt.
  const double now = time();
  const double due = now + dt_ * 1e-6;
  for (std::size_t team = 0; team < pending_.size(); ++team) {
    for (auto& [release, packet] : pending_[team].pop_due(due)) {
      (void)release;
      const double timeout = std::max(0.0, packet.command_timeout);
      for (const robot_command_t& c : packet.commands) {
        apply_command(static_cast<Team>(team), c.robot_id, c, timeout);
      }
    }
  }
}

void World::command(Team team, int id, const robot_command_t& command, double timeout) {
  apply_command(team, id, command, std::isfinite(timeout) ? std::max(0.0, timeout) : 0.0);
}

std::string command_summary(const WorldCounters& c) {
  return "commands: " + std::to_string(c.commands_applied) + " applied, " +
         c.commands_clamped.text() + " of them at a robot type's limit, " +
         std::to_string(c.commands_dropped) +
         " dropped (not finite, unknown mode, wrong wheel count), " +
         std::to_string(c.commands_unknown_robot) + " for robots not on the field, " +
         std::to_string(c.packets_dropped) + " packets dropped (bad team or time)";
}

void World::apply_command(Team team, int id, const robot_command_t& raw, double timeout) {
  Robot* r = robot(team, id);
  if (r == nullptr) {
    ++counters_.commands_unknown_robot;
    log_.warn("unknown:" + robot_name(team, id),
              "command for " + robot_name(team, id) + ", which is not on the field");
    return;
  }
  const CommandCheck check = check_command(raw, r->type());
  if (!check.accepted) {
    ++counters_.commands_dropped;
    log_.warn("robot:" + robot_name(team, id),
              "dropped command for " + robot_name(team, id) + ": " + check.problem);
    return;
  }
  if (check.clamped) {
    counters_.commands_clamped.add(check);
    log_.warn("robot:" + robot_name(team, id),
              "command for " + robot_name(team, id) + ": " + check.problem);
  }
  ++counters_.commands_applied;
  r->set_command(check.command, time(), timeout);
}

void World::step() {
  check_safety(false);
  apply_due_commands();
  apply_force_moves();
  const double now = time();
  for (auto& r : robots_) r->before_step(now, dt_);
  for (auto& r : robots_) r->update_hold(*ball_, now, perfect_dribbling_, world_.get());
  std::vector<char>& kicked = kicked_buffer_;
  kicked.assign(robots_.size(), 0);
  for (std::size_t i = 0; i < robots_.size(); ++i) {
    if (robots_[i]->try_kick(*ball_, now, dt_)) {
      kicked[i] = 1;
      ++counters_.kicks;
    }
  }
  contact_handler_->collide(space_.get(), world_.get(), contacts_.get());
  for (std::size_t i = 0; i < robots_.size(); ++i) {
    if (!kicked[i]) robots_[i]->add_dribbler_contact(*ball_, now, world_.get(), contacts_.get());
  }
  // ODE's QuickStep shuffles constraints with a process-wide generator: give
  // it this world's own state so worlds never disturb each other.
  dRandSetSeed(solver_random_state_);
  if (setup_.physics.solver == Solver::QuickStep) {
    dWorldQuickStep(world_.get(), dt_);
  } else {
    dWorldStep(world_.get(), dt_);
  }
  solver_random_state_ = dRandGetSeed();
  dJointGroupEmpty(contacts_.get());
  for (auto& r : robots_) r->after_step();
  ++step_;
  check_safety(true);
}

void World::fill_state(sim_state_t& out) const {
  out.sim_time = time();
  out.step = step_;
  out.dt = dt_;
  const dBodyID b = ball_->body();
  const dReal* p = dBodyGetPosition(b);
  const dReal* q = dBodyGetQuaternion(b);
  const dReal* v = dBodyGetLinearVel(b);
  const dReal* w = dBodyGetAngularVel(b);
  for (int k = 0; k < 3; ++k) {
    out.ball.position[k] = p[k];
    out.ball.linear_velocity[k] = v[k];
    out.ball.angular_velocity[k] = w[k];
  }
  for (int k = 0; k < 4; ++k) out.ball.orientation[k] = q[k];
  out.ball_present = true;
  out.num_robots = static_cast<int32_t>(robots_.size());
  out.robots.resize(robots_.size());
  for (std::size_t i = 0; i < robots_.size(); ++i) {
    robots_[i]->fill_state(out.robots[i], *ball_, time());
  }
}

}  // namespace ubersim::physics
