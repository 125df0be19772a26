#include "ubersim/physics/world.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <set>
#include <sstream>

#include "ubersim/config_paths.hpp"
#include "ubersim/scenario_config.hpp"

namespace ubersim::physics {
namespace {

constexpr int kMaxRobotId = 99;  // the scenario format's two-digit ids (YELLOW_0 .. BLUE_99)

std::string robot_name(Team team, int id) {
  return std::string(team_name(team)) + " " + std::to_string(id);
}

bool finite_all(const dReal* v, int n) {
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(v[i])) return false;
  }
  return true;
}

bool body_finite(dBodyID b) {
  return finite_all(dBodyGetPosition(b), 3) && finite_all(dBodyGetQuaternion(b), 4) &&
         finite_all(dBodyGetLinearVel(b), 3) && finite_all(dBodyGetAngularVel(b), 3);
}

}  // namespace

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
  world_.reset(dWorldCreate());
  dWorldID w = world_.get();
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
  return true;
}

Robot* World::robot(Team team, int id) {
  for (auto& r : robots_) {
    if (r->team() == team && r->id() == id) return r.get();
  }
  return nullptr;
}

void World::place_ball(double x, double y, double z, double vx, double vy, double vz) {
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
    ++counters_.commands_clamped;
    log_.warn("robot:" + robot_name(team, id),
              "command for " + robot_name(team, id) + ": " + check.problem);
  }
  ++counters_.commands_applied;
  r->set_command(check.command, time(), timeout);
}

void World::step() {
  check_safety(false);
  apply_due_commands();
  const double now = time();
  for (auto& r : robots_) r->before_step(now, dt_);
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

bool World::inside_walls(double x, double y, double margin) const {
  return std::abs(x) <= setup_.field.half_length_to_wall() + margin &&
         std::abs(y) <= setup_.field.half_width_to_wall() + margin;
}

bool World::body_sane(dBodyID b) const {
  if (!body_finite(b)) return false;
  const dReal* v = dBodyGetLinearVel(b);
  const dReal* w = dBodyGetAngularVel(b);
  const double max_v = setup_.physics.max_linear_speed;
  const double max_w = setup_.physics.max_angular_speed;
  return v[0] * v[0] + v[1] * v[1] + v[2] * v[2] <= max_v * max_v &&
         w[0] * w[0] + w[1] * w[1] + w[2] * w[2] <= max_w * max_w;
}

void World::check_safety(bool after_step) {
  // Beyond the walls' outer faces nothing can be legitimately. Before a step
  // this keeps a broken body away from ODE (which aborts on a non-finite
  // quaternion); after it, it keeps it out of what we publish.
  const double margin = setup_.field.wall_thickness;
  const dBodyID ball = ball_->body();
  const dReal* bp = dBodyGetPosition(ball);
  const bool ball_sane = body_sane(ball);
  if (!ball_sane || !inside_walls(bp[0], bp[1], margin) || bp[2] < -setup_.ball.radius) {
    // Over the wall or through a fault: back inside where it was last seen
    // good, on the floor, at rest.
    ++counters_.bodies_reset;
    const double r = setup_.ball.radius;
    const double x = std::clamp(ball_last_good_[0], -setup_.field.half_length_to_wall() + r,
                                setup_.field.half_length_to_wall() - r);
    const double y = std::clamp(ball_last_good_[1], -setup_.field.half_width_to_wall() + r,
                                setup_.field.half_width_to_wall() - r);
    log_.warn("reset:ball",
              std::string("ball ") +
                  (ball_sane ? "left the field" : "had a non-finite or runaway state") +
                  ": put back at (" + std::to_string(x) + ", " + std::to_string(y) + ") at rest");
    place_ball(x, y, 0, 0, 0, 0);
  } else if (after_step) {
    ball_last_good_ = {bp[0], bp[1], bp[2]};
  }

  const double upright_limit = std::cos(setup_.physics.tip_angle);
  for (auto& r : robots_) {
    body_buffer_.clear();
    r->bodies(body_buffer_);
    bool sane = true;
    for (dBodyID b : body_buffer_) sane = sane && body_sane(b);
    double x, y;
    r->position(x, y);
    if (!sane || !inside_walls(x, y, margin)) {
      ++counters_.bodies_reset;
      const PlanarState good = r->last_good_state();
      log_.warn("reset:" + robot_name(r->team(), r->id()),
                robot_name(r->team(), r->id()) +
                    (sane ? " left the field" : " had a non-finite or runaway state") +
                    ": put back at (" + std::to_string(good.x) + ", " + std::to_string(good.y) +
                    ") at rest");
      PlanarState rest = good;
      rest.vx = rest.vy = rest.omega = 0;
      r->place(rest);
      continue;
    }
    if (!after_step) continue;
    if (r->uprightness() < upright_limit) {
      ++counters_.robots_set_upright;
      log_.warn("upright:" + robot_name(r->team(), r->id()),
                robot_name(r->team(), r->id()) + " tipped over: set upright where it was");
      PlanarState rest = r->planar_state();
      rest.vx = rest.vy = rest.omega = 0;
      r->place(rest);
    }
    r->remember_good_state();
  }
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

void World::move_ball_out_of_robots(std::string& notes) {
  const double r = setup_.ball.radius;
  for (auto& robot : robots_) {
    const dReal* bp = ball_->position();
    const PlanarState s = robot->planar_state();
    const double c = std::cos(s.heading);
    const double sn = std::sin(s.heading);
    const Vec2 local{c * (bp[0] - s.x) + sn * (bp[1] - s.y),
                     -sn * (bp[0] - s.x) + c * (bp[1] - s.y)};
    if (bp[2] > robot->type().height + r) continue;  // above it
    Vec2 closest;
    Vec2 normal;
    const double distance = robot->outline().signed_distance(local, &closest, &normal);
    if (distance >= r) continue;
    const Vec2 out_local = closest + (r + setup_.physics.contact_surface_layer) * normal;
    const Vec2 out = rotate(out_local, c, sn);
    const dReal* v = ball_->velocity();
    place_ball(s.x + out.x, s.y + out.y, bp[2], v[0], v[1], v[2]);
    notes += "ball moved out of " + robot_name(robot->team(), robot->id()) + "; ";
  }
}

PlaceOutcome World::place(const sim_control_t& request, bool remove_all_first) {
  PlaceOutcome outcome;
  // Check everything first: a bad request changes nothing.
  std::set<std::pair<int, int>> seen;
  std::vector<std::shared_ptr<const RobotTypeConfig>> types(request.robots.size());
  for (std::size_t i = 0; i < request.robots.size(); ++i) {
    const robot_placement_t& p = request.robots[i];
    if (p.team != 0 && p.team != 1) {
      outcome.message = "robot " + std::to_string(i) + ": unknown team " + std::to_string(p.team);
      return outcome;
    }
    const Team team = static_cast<Team>(p.team);
    if (p.robot_id < 0 || p.robot_id > kMaxRobotId) {
      outcome.message =
          "robot id " + std::to_string(p.robot_id) + " outside 0.." + std::to_string(kMaxRobotId);
      return outcome;
    }
    if (!seen.insert({p.team, p.robot_id}).second) {
      outcome.message = robot_name(team, p.robot_id) + " placed twice in one request";
      return outcome;
    }
    if (!p.present) continue;
    for (double v : {p.x, p.y, p.orientation, p.vx, p.vy, p.omega}) {
      if (!std::isfinite(v)) {
        outcome.message = robot_name(team, p.robot_id) + ": non-finite placement";
        return outcome;
      }
    }
    if (!p.robot_type.empty()) {
      try {
        types[i] = setup_.robot_types(p.robot_type);
      } catch (const std::exception& e) {
        outcome.message =
            robot_name(team, p.robot_id) + ": robot type '" + p.robot_type + "': " + e.what();
        return outcome;
      }
    } else if (remove_all_first || robot(team, p.robot_id) == nullptr) {
      outcome.message = robot_name(team, p.robot_id) + " is new: it needs a robot_type";
      return outcome;
    }
  }
  if (request.has_ball) {
    for (double v : {request.ball.position[0], request.ball.position[1], request.ball.position[2],
                     request.ball.linear_velocity[0], request.ball.linear_velocity[1],
                     request.ball.linear_velocity[2]}) {
      if (!std::isfinite(v)) {
        outcome.message = "non-finite ball placement";
        return outcome;
      }
    }
  }

  std::string notes;
  int placed = 0;
  int removed = 0;
  if (remove_all_first) {
    removed = static_cast<int>(robots_.size());
    robots_.clear();
  }
  for (std::size_t i = 0; i < request.robots.size(); ++i) {
    const robot_placement_t& p = request.robots[i];
    const Team team = static_cast<Team>(p.team);
    if (!p.present) {
      if (remove_robot(team, p.robot_id)) ++removed;
      continue;
    }
    Robot* existing = robot(team, p.robot_id);
    const auto type = types[i] ? types[i] : existing->type_ptr();
    // Inside the walls, and no faster than the robot can go.
    const double limit_x = setup_.field.half_length_to_wall() - type->radius;
    const double limit_y = setup_.field.half_width_to_wall() - type->radius;
    PlanarState s;
    s.x = std::clamp(p.x, -limit_x, limit_x);
    s.y = std::clamp(p.y, -limit_y, limit_y);
    if (s.x != p.x || s.y != p.y)
      notes += robot_name(team, p.robot_id) + " kept inside the walls; ";
    s.heading = p.orientation;
    const double speed = std::hypot(p.vx, p.vy);
    const double scale = speed > type->max_speed ? type->max_speed / speed : 1.0;
    s.vx = p.vx * scale;
    s.vy = p.vy * scale;
    s.omega = std::clamp(p.omega, -type->max_angular_speed, type->max_angular_speed);
    if (scale != 1.0 || s.omega != p.omega) {
      notes += robot_name(team, p.robot_id) + " velocity clamped to its limits; ";
    }
    if (existing != nullptr && existing->type_ptr() == type) {
      existing->place(s);
      existing->remember_good_state();
    } else {
      add_robot(team, p.robot_id, type->name, s);
    }
    ++placed;
  }
  if (request.has_ball) {
    const double r = setup_.ball.radius;
    const double limit_x = setup_.field.half_length_to_wall() - r;
    const double limit_y = setup_.field.half_width_to_wall() - r;
    const double x = std::clamp(request.ball.position[0], -limit_x, limit_x);
    const double y = std::clamp(request.ball.position[1], -limit_y, limit_y);
    if (x != request.ball.position[0] || y != request.ball.position[1]) {
      notes += "ball kept inside the walls; ";
    }
    place_ball(x, y, request.ball.position[2], request.ball.linear_velocity[0],
               request.ball.linear_velocity[1], request.ball.linear_velocity[2]);
  }
  // Wherever robots and ball ended up, the ball is never left inside a robot.
  move_ball_out_of_robots(notes);
  std::ostringstream message;
  message << "placed " << placed << " robot(s), removed " << removed;
  if (request.has_ball) message << ", placed the ball";
  if (!notes.empty()) message << "; " << notes.substr(0, notes.size() - 2);
  outcome.ok = true;
  outcome.message = message.str();
  return outcome;
}

}  // namespace ubersim::physics
