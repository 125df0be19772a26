#include "ubersim/ssl_bridge/sim_control_translation.hpp"

#include <cmath>
#include <set>
#include <ubersim/ball_placement_t.hpp>
#include <ubersim/team_t.hpp>

namespace ubersim::ssl {
namespace {

const robot_state_t* find_robot(const sim_state_t* state, int8_t team, int32_t id) {
  if (state == nullptr) return nullptr;
  for (const robot_state_t& robot : state->robots) {
    if (robot.team == team && robot.robot_id == id) return &robot;
  }
  return nullptr;
}

bool all_finite(std::initializer_list<double> values) {
  for (double v : values) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

std::string robot_name(const RobotId& id) {
  return std::string(id.team() == YELLOW ? "yellow " : "blue ") + std::to_string(id.id());
}

std::string type_for_new_robot(const SpecTypes& types, int8_t team, int32_t id,
                               const std::string& fallback) {
  if (const auto own = types.by_robot.find({team, id}); own != types.by_robot.end()) {
    return own->second;
  }
  if (const auto shared = types.by_team.find(team); shared != types.by_team.end()) {
    return shared->second;
  }
  return fallback;
}

// Adds the placement for one TeleportRobot, or an error. Returns the
// placement's (team, id) when one was added.
bool translate_robot(const TeleportRobot& in, const sim_state_t* state,
                     const SimControlSettings& settings, sim_control_t& place, Errors& errors) {
  if (!in.id().has_id() || (in.id().team() != YELLOW && in.id().team() != BLUE)) {
    add_error(errors, kErrorInvalid, "teleport_robot needs an id with team YELLOW or BLUE");
    return false;
  }
  const std::string name = robot_name(in.id());
  if (!all_finite({in.x(), in.y(), in.orientation(), in.v_x(), in.v_y(), in.v_angular()})) {
    add_error(errors, kErrorInvalid, "teleport_robot with a non-finite value (" + name + ")");
    return false;
  }
  robot_placement_t placement{};
  placement.team = in.id().team() == YELLOW ? int8_t{team_t::YELLOW} : int8_t{team_t::BLUE};
  placement.robot_id = static_cast<int32_t>(in.id().id());
  const robot_state_t* current = find_robot(state, placement.team, placement.robot_id);
  if (in.has_present() && !in.present()) {
    placement.present = false;
    place.robots.push_back(placement);
    return true;
  }
  placement.present = true;
  // Nothing but the id (and by_force = false): only end a move by force.
  const bool only_id = !in.has_x() && !in.has_y() && !in.has_orientation() && !in.has_v_x() &&
                       !in.has_v_y() && !in.has_v_angular() && !in.has_present();
  if (in.by_force() || only_id) {
    if (current == nullptr) {
      add_error(errors, kErrorUnknownRobot,
                name + " is not on the field; by_force moves only robots on the field");
      return false;
    }
    placement.mode = in.by_force() ? ball_placement_t::BY_FORCE : ball_placement_t::END_FORCE;
    placement.x = in.has_x() ? in.x() : current->x;
    placement.y = in.has_y() ? in.y() : current->y;
    placement.orientation = in.has_orientation() ? in.orientation() : current->orientation;
    place.robots.push_back(placement);
    return true;
  }
  if (current == nullptr) {
    if (!in.has_present()) {
      add_error(errors, kErrorUnknownRobot,
                name + " is not on the field; set present = true to add it");
      return false;
    }
    if (!in.has_x() || !in.has_y()) {
      add_error(errors, kErrorInvalid, "adding " + name + " needs x and y");
      return false;
    }
    placement.robot_type = type_for_new_robot(settings.spec_types, placement.team,
                                              placement.robot_id, settings.new_robot_type);
  }
  placement.x = in.has_x() ? in.x() : current->x;
  placement.y = in.has_y() ? in.y() : current->y;
  placement.orientation =
      in.has_orientation() ? in.orientation() : (current ? current->orientation : 0.0);
  placement.vx = in.v_x();
  placement.vy = in.v_y();
  placement.omega = in.v_angular();
  place.robots.push_back(placement);
  return true;
}

// Whether a robot at (x, y) would overlap a robot other than `self` (as the
// state has them, or as this request already places them).
bool spot_taken(double x, double y, const robot_state_t& self, const sim_state_t& state,
                const sim_control_t& place, double robot_radius) {
  const double apart = 2 * robot_radius + 0.01;  // m
  for (const robot_state_t& other : state.robots) {
    if (other.team == self.team && other.robot_id == self.robot_id) continue;
    if (std::hypot(other.x - x, other.y - y) < apart) return true;
  }
  for (const robot_placement_t& other : place.robots) {
    if (other.team == self.team && other.robot_id == self.robot_id) continue;
    if (std::hypot(other.x - x, other.y - y) < apart) return true;
  }
  return false;
}

// teleport_safely: robots that would overlap the ball at its new place are
// pushed radially out of the way and stopped, onto a spot no other robot
// holds (the nearest direction to straight out that is free; pushed onto
// another robot, a standing robot would squeeze it into the ball).
void clear_ball_target(double bx, double by, const sim_state_t* state,
                       const SimControlSettings& settings, sim_control_t& place) {
  if (state == nullptr) return;
  const double clearance = settings.robot_radius + settings.ball_radius + 0.01;  // m
  std::set<std::pair<int, int>> already;
  for (const robot_placement_t& p : place.robots) already.insert({p.team, p.robot_id});
  for (const robot_state_t& robot : state->robots) {
    if (already.count({robot.team, robot.robot_id}) != 0) continue;
    const double dx = robot.x - bx, dy = robot.y - by;
    const double distance = std::hypot(dx, dy);
    if (distance >= clearance) continue;
    robot_placement_t p{};
    p.team = robot.team;
    p.robot_id = robot.robot_id;
    p.present = true;
    p.orientation = robot.orientation;
    const double out = distance > 1e-6 ? std::atan2(dy, dx) : 0.0;
    constexpr int kTries = 12;  // straight out, then 15, 30, ... degrees either side
    for (int i = 0; i < kTries; ++i) {
      const double turn = (i + 1) / 2 * (M_PI / 12) * (i % 2 == 0 ? 1 : -1);
      p.x = bx + std::cos(out + turn) * clearance;
      p.y = by + std::sin(out + turn) * clearance;
      if (!spot_taken(p.x, p.y, robot, *state, place, settings.robot_radius)) break;
      if (i == kTries - 1) {  // nowhere free nearby: straight out, as before
        p.x = bx + std::cos(out) * clearance;
        p.y = by + std::sin(out) * clearance;
      }
    }
    place.robots.push_back(p);
  }
}

void translate_ball(const TeleportBall& in, const sim_state_t* state,
                    const SimControlSettings& settings, sim_control_t& place, Errors& errors) {
  if (!all_finite({in.x(), in.y(), in.z(), in.vx(), in.vy(), in.vz()})) {
    add_error(errors, kErrorInvalid, "teleport_ball with a non-finite value");
    return;
  }
  if ((!in.has_x() || !in.has_y()) && state == nullptr &&
      (in.by_force() || in.has_x() || in.has_y() || in.has_z() || in.has_vx() || in.has_vy() ||
       in.has_vz())) {
    add_error(errors, kErrorInvalid,
              "teleport_ball without x and y before physics reported where the ball is");
    return;
  }
  // No field at all (by_force = false): only end a move by force, no teleport.
  const bool nothing = !in.has_x() && !in.has_y() && !in.has_z() && !in.has_vx() && !in.has_vy() &&
                       !in.has_vz() && !in.by_force();
  place.has_ball = true;
  place.ball.mode = in.by_force() ? ball_placement_t::BY_FORCE
                    : nothing     ? ball_placement_t::END_FORCE
                                  : ball_placement_t::TELEPORT;
  place.ball.rolling = in.roll();
  place.ball.position[0] = in.has_x() ? in.x() : (state ? state->ball.position[0] : 0.0);
  place.ball.position[1] = in.has_y() ? in.y() : (state ? state->ball.position[1] : 0.0);
  place.ball.position[2] = in.z();
  place.ball.linear_velocity[0] = in.vx();
  place.ball.linear_velocity[1] = in.vy();
  place.ball.linear_velocity[2] = in.vz();
  if (in.teleport_safely()) {
    clear_ball_target(place.ball.position[0], place.ball.position[1], state, settings, place);
  }
}

sim_control_t request(int8_t action) {
  sim_control_t r{};
  r.action = action;
  return r;
}

void translate_speed(float speed, const sim_state_t* state, SimControlTranslation& out) {
  if (!std::isfinite(speed) || speed < 0) {
    add_error(out.errors, kErrorInvalid, "simulation_speed must be >= 0");
    return;
  }
  if (speed == 0) {  // the protocol's 0 stops the simulation
    out.requests.push_back(request(sim_control_t::PAUSE));
    return;
  }
  sim_control_t speed_request = request(sim_control_t::SET_SPEED);
  speed_request.speed_factor = speed;
  out.requests.push_back(speed_request);
  if (state == nullptr || state->paused) out.requests.push_back(request(sim_control_t::RESUME));
}

void translate_config(const SimulatorConfig& config, const SimControlSettings& settings,
                      SimControlTranslation& out) {
  if (config.has_geometry()) {
    GeometryChange change = translate_geometry(config.geometry(), settings.current_field);
    out.errors.insert(out.errors.end(), change.errors.begin(), change.errors.end());
    if (change.field_config) {
      sim_control_t set_field = request(sim_control_t::SET_FIELD);
      set_field.field_config = *change.field_config;
      out.requests.push_back(set_field);
    }
    out.cameras = change.cameras;
  }
  if (config.has_realism_config()) {
    RealismTranslation realism = translate_realism(config.realism_config());
    out.errors.insert(out.errors.end(), realism.errors.begin(), realism.errors.end());
    out.realism = realism.realism;
    if (realism.perfect_dribbling) {  // physics owns the dribblers
      sim_control_t dribbling = request(sim_control_t::SET_DRIBBLING);
      dribbling.perfect_dribbling = *realism.perfect_dribbling;
      out.requests.push_back(dribbling);
    }
  }
  if (config.has_vision_port()) {
    if (config.vision_port() == 0 || config.vision_port() > 65535) {
      add_error(out.errors, kErrorInvalid, "config.vision_port must be 1..65535");
    } else {
      out.vision_port = static_cast<int>(config.vision_port());
    }
  }
}

// Each spec becomes a robot type (DEFINE_ROBOT_TYPE), then the robots on the
// field it names are rebuilt from it where they stand (PLACE with the type).
void translate_specs(const SimulatorConfig& config, const sim_state_t* state,
                     SimControlSettings& settings, SimControlTranslation& out) {
  if (settings.base_robot_type == nullptr) {
    add_error(out.errors, kErrorUnsupported,
              "config.robot_specs: this bridge has no base robot type to apply them to");
    return;
  }
  RobotSpecsTranslation specs =
      translate_robot_specs(config.robot_specs(), *settings.base_robot_type);
  out.errors.insert(out.errors.end(), specs.errors.begin(), specs.errors.end());
  for (DefinedRobotType& type : specs.types) {
    sim_control_t define = request(sim_control_t::DEFINE_ROBOT_TYPE);
    define.robot_type_name = type.name;
    define.robot_type_config = type.config_text;
    out.requests.push_back(define);
    sim_control_t place = request(sim_control_t::PLACE);
    if (state != nullptr) {
      for (const robot_state_t& robot : state->robots) {
        if (robot.team != type.team || (type.robot_id && *type.robot_id != robot.robot_id)) {
          continue;
        }
        robot_placement_t p{};
        p.team = robot.team;
        p.robot_id = robot.robot_id;
        p.robot_type = type.name;
        p.present = true;
        p.x = robot.x;
        p.y = robot.y;
        p.orientation = robot.orientation;
        p.vx = robot.vx;
        p.vy = robot.vy;
        p.omega = robot.omega;
        place.robots.push_back(p);
      }
    }
    place.num_robots = static_cast<int32_t>(place.robots.size());
    if (place.num_robots > 0) out.requests.push_back(place);
    settings.spec_types.record(type);
    out.defined_types.push_back(std::move(type));
  }
}

}  // namespace

void SpecTypes::record(const DefinedRobotType& type) {
  if (type.robot_id) {
    by_robot[{type.team, *type.robot_id}] = type.name;
  } else {
    by_team[type.team] = type.name;
    // A team-wide spec replaces the robots' own ones from before.
    for (auto it = by_robot.begin(); it != by_robot.end();) {
      it = it->first.first == type.team ? by_robot.erase(it) : std::next(it);
    }
  }
}

SimControlTranslation translate_simulator_command(const SimulatorCommand& command,
                                                  const sim_state_t* state,
                                                  const SimControlSettings& given_settings) {
  SimControlTranslation out;
  // Specs first, so robots the same command adds are built from them.
  SimControlSettings settings = given_settings;
  if (command.has_config() && command.config().robot_specs_size() > 0) {
    translate_specs(command.config(), state, settings, out);
  }
  if (command.has_control()) {
    const SimulatorControl& control = command.control();
    sim_control_t place = request(sim_control_t::PLACE);
    for (const TeleportRobot& robot : control.teleport_robot()) {
      translate_robot(robot, state, settings, place, out.errors);
    }
    if (control.has_teleport_ball()) {
      translate_ball(control.teleport_ball(), state, settings, place, out.errors);
    }
    place.num_robots = static_cast<int32_t>(place.robots.size());
    if (place.has_ball || place.num_robots > 0) out.requests.push_back(place);
    if (control.has_simulation_speed()) translate_speed(control.simulation_speed(), state, out);
  }
  if (command.has_config()) translate_config(command.config(), settings, out);
  return out;
}

}  // namespace ubersim::ssl
