#include "ubersim/physics/robot.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "ubersim/physics/heading.hpp"

namespace ubersim::physics {
namespace {

// Moves `value` towards `target` by at most `max_step` (no limit when <= 0).
double approach(double value, double target, double max_step) {
  if (max_step <= 0) return target;
  return value + std::clamp(target - value, -max_step, max_step);
}

// The angular set-point's step: a change against the current turning (the
// sign differs, so it slows the turn) is braking, anything else speeds up.
// This is how the ER-Force simulator bounds each axis (simrobot.cpp, bound()).
double approach_angular(double value, double target, double speedup_step, double brake_step) {
  const bool braking = value != 0 && std::signbit(target - value) != std::signbit(value);
  return approach(value, target, braking ? brake_step : speedup_step);
}

// How much of the set-point change (dvx, dvy) one step may make, as a factor
// in [0, 1] that keeps its direction. The part of the change against the
// current velocity (vx, vy) reduces the speed: it is braking and bounded by
// `brake_step`; the rest (along the velocity, or across it) speeds up or turns
// it and is bounded by `speedup_step` (ER-Force's rule per axis, made
// independent of the axes). The two bound an ellipse; when they are equal it
// is the plain length limit. A step <= 0 means no limit on that part.
double velocity_change_scale(double vx, double vy, double dvx, double dvy, double speedup_step,
                             double brake_step) {
  const double change = std::sqrt(dvx * dvx + dvy * dvy);
  if (speedup_step == brake_step) {
    return (speedup_step > 0 && change > speedup_step) ? speedup_step / change : 1;
  }
  const double speed = std::sqrt(vx * vx + vy * vy);
  const double along = speed > 0 ? (dvx * vx + dvy * vy) / speed : 0;  // < 0: against the motion
  const double braking = along < 0 ? -along : 0;
  const double rest = std::sqrt(std::max(0.0, change * change - braking * braking));
  const auto share = [](double part, double step) { return step > 0 ? part / step : 0.0; };
  const double b = share(braking, brake_step), r = share(rest, speedup_step);
  const double reach = std::sqrt(b * b + r * r);  // > 1: beyond what one step allows
  return reach > 1 ? 1 / reach : 1;
}

}  // namespace

Robot::Robot(dWorldID world, dSpaceID world_space, const PhysicsConfig& physics,
             const BallConfig& ball, std::shared_ptr<const RobotTypeConfig> type, Team team, int id)
    : type_(std::move(type)),
      team_(team),
      id_(id),
      physics_(physics),
      ball_radius_(ball.radius),
      ball_mass_(ball.mass),
      kinematics_(*type_) {
  const RobotTypeConfig& t = *type_;
  const double origin = chassis_origin_height(t);
  // With a mouth, the main body is cut flat at the kicker; the front parts
  // around the mouth are added below, once the chassis body exists.
  outline_ = ChassisOutline::make(t.radius, t.kicker_distance, physics.chassis_outline_segments,
                                  t.ground_clearance - origin, t.height - origin);
  if (t.has_mouth() && t.mouth_height - t.ground_clearance < 2 * ball_radius_) {
    throw std::invalid_argument(
        "robot type '" + t.name + "': its mouth (MOUTH_HEIGHT " + std::to_string(t.mouth_height) +
        " m) is too low for a ball of radius " + std::to_string(ball_radius_) + " m");
  }
  if (t.has_dribbler()) {
    // Roller axis placed so that it just touches a ball resting against the
    // kicker face: a held ball sits on the face, where the kicker reaches it.
    const double reach = ball_radius_ + t.dribbler_roller_radius;
    const double rise = t.dribbler_height - ball_radius_;
    if (std::abs(rise) >= reach) {
      throw std::invalid_argument(
          "robot type '" + t.name + "': a dribbler at height " + std::to_string(t.dribbler_height) +
          " m cannot touch a ball of radius " + std::to_string(ball_radius_) + " m");
    }
    roller_x_ = t.kicker_distance + ball_radius_ - std::sqrt(reach * reach - rise * rise);
  }
  space_ = make_simple_space(world_space);
  dGeomID space_geom = reinterpret_cast<dGeomID>(space_.get());
  dGeomSetCategoryBits(space_geom, collide_bits::kChassis | collide_bits::kWheel);
  dGeomSetCollideBits(space_geom, collide_bits::kGround | collide_bits::kWall |
                                      collide_bits::kBall | collide_bits::kChassis);
  chassis_tag_.kind = GeomKind::Chassis;
  chassis_tag_.robot = this;
  DriveContext context;
  context.world = world;
  context.space = space_.get();
  context.type = type_.get();
  context.physics = &physics_;
  context.kinematics = &kinematics_;
  context.outline = &outline_;
  context.chassis_tag = &chassis_tag_;
  context.robot = this;
  drive_ =
      t.model == DriveModel::Jointed ? make_jointed_drive(context) : make_planar_drive(context);
  wheel_targets_.assign(t.wheels.size(), 0.0);
  if (t.has_mouth())
    add_mouth_parts(t.ground_clearance - origin, t.height - origin, t.mouth_height - origin);
}

// The front around a mouth, as three more prisms on the chassis body: a lip
// above the mouth (flat front to kicker face, flat front's width) and a pillar
// either side (the round part of the body between the two cuts), full height.
void Robot::add_mouth_parts(double z_bottom, double z_top, double z_mouth) {
  const RobotTypeConfig& t = *type_;
  const double kicker = t.kicker_distance, front = t.front_distance, r = t.radius;
  const double half_front = std::sqrt(std::max(0.0, r * r - front * front));
  const double half_kicker = std::sqrt(std::max(0.0, r * r - kicker * kicker));
  front_parts_.reserve(3);
  front_parts_.push_back(ChassisOutline::polygon(
      {{kicker, -half_front}, {front, -half_front}, {front, half_front}, {kicker, half_front}},
      z_mouth, z_top));
  if (half_kicker - half_front > 1e-6) {
    // Left pillar, counter-clockwise: along the mouth's side, round the arc.
    constexpr int kArcSegments = 4;
    const double from = std::atan2(half_front, front), to = std::atan2(half_kicker, kicker);
    std::vector<Vec2> left{{kicker, half_front}};
    for (int i = 0; i <= kArcSegments; ++i) {
      const double a = from + (to - from) * i / kArcSegments;
      left.push_back({r * std::cos(a), r * std::sin(a)});
    }
    std::vector<Vec2> right;  // the mirror image, still counter-clockwise
    for (auto it = left.rbegin(); it != left.rend(); ++it) right.push_back({it->x, -it->y});
    front_parts_.push_back(ChassisOutline::polygon(std::move(left), z_bottom, z_top));
    front_parts_.push_back(ChassisOutline::polygon(std::move(right), z_bottom, z_top));
  }
  for (const ChassisOutline& part : front_parts_) {
    GeomHandle& geom = front_geoms_.emplace_back(create_chassis_geom(space_.get(), &part));
    dGeomSetBody(geom.get(), drive_->chassis());
    tag_geom(geom.get(), &chassis_tag_);
  }
}

void Robot::place(const PlanarState& state) {
  release_ball();
  drive_->place(state);
  setpoint_vx_ = state.vx;
  setpoint_vy_ = state.vy;
  setpoint_omega_ = state.omega;
}

PlanarState Robot::planar_state() const {
  const dBodyID body = drive_->chassis();
  const dReal* p = dBodyGetPosition(body);
  const dReal* R = dBodyGetRotation(body);
  const dReal* v = dBodyGetLinearVel(body);
  const dReal* w = dBodyGetAngularVel(body);
  PlanarState s;
  s.x = p[0];
  s.y = p[1];
  s.heading = heading_angle(R);
  s.vx = v[0];
  s.vy = v[1];
  s.omega = w[2];
  return s;
}

void Robot::position(double& x, double& y) const {
  const dReal* p = dBodyGetPosition(drive_->chassis());
  x = p[0];
  y = p[1];
}

void Robot::heading_vector(double& c, double& s) const {
  const Vec2 direction = heading_direction(dBodyGetRotation(drive_->chassis()));
  c = direction.x;
  s = direction.y;
}

void Robot::remember_good_state() {
  position(good_x_, good_y_);
  heading_vector(good_c_, good_s_);
}

PlanarState Robot::last_good_state() const {
  PlanarState s;
  s.x = good_x_;
  s.y = good_y_;
  s.heading = std::atan2(good_s_, good_c_);
  return s;
}

double Robot::uprightness() const {
  return dBodyGetRotation(drive_->chassis())[10];
}

void Robot::set_command(const RobotCommand& command, double now, double timeout) {
  command_ = command;
  last_command_time_ = now;
  command_timeout_ = timeout;
}

const RobotCommand& Robot::effective_command(double now) const {
  static const RobotCommand stop{};
  const bool timed_out = command_timeout_ > 0 && last_command_time_ >= 0 &&
                         now - last_command_time_ > command_timeout_;
  return timed_out ? stop : command_;
}

void Robot::before_step(double now, double dt) {
  const RobotTypeConfig& t = *type_;
  const RobotCommand& command = effective_command(now);
  double c, sn;
  heading_vector(c, sn);
  if (command.mode == CommandMode::WheelSpeeds) {
    // Raw motor set-points; the velocity set-point follows for a smooth switch back.
    wheel_targets_ = command.wheel_speeds;
    Eigen::VectorXd w(static_cast<Eigen::Index>(wheel_targets_.size()));
    for (std::size_t i = 0; i < wheel_targets_.size(); ++i) {
      w(static_cast<Eigen::Index>(i)) = wheel_targets_[i];
    }
    const Eigen::Vector3d v = kinematics_.velocity(w);
    setpoint_vx_ = c * v(0) - sn * v(1);
    setpoint_vy_ = sn * v(0) + c * v(1);
    setpoint_omega_ = v(2);
  } else {
    double target_vx = command.vx;
    double target_vy = command.vy;
    if (command.mode == CommandMode::LocalVelocity) {
      target_vx = c * command.vx - sn * command.vy;
      target_vy = sn * command.vx + c * command.vy;
    }
    // The on-board acceleration limits act on the field-frame velocity: that
    // is the acceleration the robot's mass actually sees. Speeding up and
    // braking have limits of their own (equal unless the type says otherwise).
    const double dvx = target_vx - setpoint_vx_;
    const double dvy = target_vy - setpoint_vy_;
    const double scale =
        velocity_change_scale(setpoint_vx_, setpoint_vy_, dvx, dvy, t.max_acceleration * dt,
                              t.max_brake_acceleration * dt);
    setpoint_vx_ += dvx * scale;
    setpoint_vy_ += dvy * scale;
    setpoint_omega_ =
        approach_angular(setpoint_omega_, command.omega, t.max_angular_acceleration * dt,
                         t.max_angular_brake_acceleration * dt);
    const double local[3] = {c * setpoint_vx_ + sn * setpoint_vy_,
                             -sn * setpoint_vx_ + c * setpoint_vy_, setpoint_omega_};
    // w = T^-1 v, written out: this runs for every robot at every step.
    const Eigen::MatrixXd& inverse = kinematics_.inverse();
    double fastest = 0;
    for (std::size_t i = 0; i < wheel_targets_.size(); ++i) {
      const auto row = static_cast<Eigen::Index>(i);
      wheel_targets_[i] =
          inverse(row, 0) * local[0] + inverse(row, 1) * local[1] + inverse(row, 2) * local[2];
      fastest = std::max(fastest, std::abs(wheel_targets_[i]));
    }
    // Out of motor speed: slow every wheel alike, so the direction holds.
    if (fastest > t.motor_max_speed) {
      for (double& w : wheel_targets_) w *= t.motor_max_speed / fastest;
    }
  }
  drive_->drive(wheel_targets_, dt);
}

void Robot::ball_in_robot_frame(const Ball& ball, double local[3]) const {
  const dBodyID body = drive_->chassis();
  const dReal* p = dBodyGetPosition(body);
  const dReal* b = ball.position();
  double fx, fy;
  heading_vector(fx, fy);
  const double dx = b[0] - p[0];
  const double dy = b[1] - p[1];
  local[0] = fx * dx + fy * dy;
  local[1] = -fy * dx + fx * dy;
  local[2] = b[2];  // height above the floor
}

bool Robot::ball_at_kicker(const Ball& ball) const {
  const RobotTypeConfig& t = *type_;
  double local[3];
  ball_in_robot_frame(ball, local);
  const double half_width = std::max(t.kicker_width, t.dribbler_width) / 2;
  return local[0] >= t.kicker_distance &&
         local[0] <= t.kicker_distance + ball_radius_ + t.kicker_reach &&
         std::abs(local[1]) <= half_width && local[2] <= ball_radius_ + t.kicker_reach;
}

bool Robot::kicker_charged(double now) const {
  return type_->has_kicker() && now - last_kick_time_ >= type_->kicker_recharge_time;
}

bool Robot::try_kick(Ball& ball, double now, double dt) {
  const RobotCommand& command = effective_command(now);
  const bool chip = command.chip_speed > 0;
  if (!chip && command.kick_speed <= 0) return false;
  if (!kicker_charged(now) || !ball_at_kicker(ball)) return false;
  release_ball();  // a held ball leaves with the kick
  const dBodyID body = drive_->chassis();
  const Vec2 forward = heading_direction(dBodyGetRotation(body));
  const double fx = forward.x;
  const double fy = forward.y;
  const dReal* b = ball.position();
  dVector3 base;
  dBodyGetPointVel(body, b[0], b[1], b[2], base);
  double v[3];
  if (chip) {
    const double along = command.chip_speed * std::cos(command.chip_angle);
    v[0] = base[0] + along * fx;
    v[1] = base[1] + along * fy;
    v[2] = command.chip_speed * std::sin(command.chip_angle);
  } else {
    v[0] = base[0] + command.kick_speed * fx;
    v[1] = base[1] + command.kick_speed * fy;
    v[2] = 0;
  }
  const dReal* old = ball.velocity();
  const double impulse[3] = {ball_mass_ * (v[0] - old[0]), ball_mass_ * (v[1] - old[1]),
                             ball_mass_ * (v[2] - old[2])};
  dBodySetLinearVel(ball.body(), v[0], v[1], v[2]);
  dBodySetAngularVel(ball.body(), 0, 0, 0);
  // Newton's third law over the coming step, at the ball: no joint, nothing stiff.
  dBodyAddForceAtPos(body, -impulse[0] / dt, -impulse[1] / dt, -impulse[2] / dt, b[0], b[1], b[2]);
  last_kick_time_ = now;
  return true;
}

void Robot::update_hold(const Ball& ball, double now, bool perfect_dribbling, dWorldID world) {
  const bool dribbling = type_->has_dribbler() && effective_command(now).dribbler_speed != 0;
  if (!perfect_dribbling || !dribbling) {
    release_ball();
    return;
  }
  if (hold_ || !ball_at_kicker(ball)) return;
  // Where the ball is now, relative to the robot, is where it stays.
  const dReal* b = ball.position();
  hold_.reset(dJointCreateBall(world, nullptr));
  dJointAttach(hold_.get(), drive_->chassis(), ball.body());
  dJointSetBallAnchor(hold_.get(), b[0], b[1], b[2]);
}

void Robot::add_dribbler_contact(const Ball& ball, double now, dWorldID world,
                                 dJointGroupID group) const {
  const RobotTypeConfig& t = *type_;
  if (!t.has_dribbler() || hold_) return;  // a held ball needs no roller
  const RobotCommand& command = effective_command(now);
  if (command.dribbler_speed == 0) return;
  double local[3];
  ball_in_robot_frame(ball, local);
  // Nearest point of the roller's axis to the ball centre (robot frame).
  const double axis_y = std::clamp(local[1], -t.dribbler_width / 2, t.dribbler_width / 2);
  const double gap[3] = {local[0] - roller_x_, local[1] - axis_y, local[2] - t.dribbler_height};
  const double distance = std::sqrt(gap[0] * gap[0] + gap[1] * gap[1] + gap[2] * gap[2]);
  const double touch = ball_radius_ + t.dribbler_roller_radius;
  if (distance > touch + t.kicker_reach || distance < 1e-9 || local[0] < roller_x_) return;

  const dBodyID body = drive_->chassis();
  const Vec2 forward = heading_direction(dBodyGetRotation(body));
  const double fx = forward.x;
  const double fy = forward.y;
  // Robot frame -> field frame (upright): x forward, y left, z up.
  auto to_field = [&](const double v[3], double out[3]) {
    out[0] = fx * v[0] - fy * v[1];
    out[1] = fy * v[0] + fx * v[1];
    out[2] = v[2];
  };
  const double n_local[3] = {gap[0] / distance, gap[1] / distance, gap[2] / distance};
  double normal[3];
  to_field(n_local, normal);
  const double roller_axis_local[3] = {0, 1, 0};
  double roller_axis[3];
  to_field(roller_axis_local, roller_axis);
  // Direction the roller's surface moves at the contact for backspin: down
  // and back along the ball's near side (axis x normal).
  double fdir[3] = {roller_axis[1] * normal[2] - roller_axis[2] * normal[1],
                    roller_axis[2] * normal[0] - roller_axis[0] * normal[2],
                    roller_axis[0] * normal[1] - roller_axis[1] * normal[0]};
  const double fnorm = std::sqrt(fdir[0] * fdir[0] + fdir[1] * fdir[1] + fdir[2] * fdir[2]);
  if (fnorm < 1e-9) return;
  const dReal* b = ball.position();
  dContact contact{};
  contact.geom.pos[0] = b[0] - normal[0] * ball_radius_;
  contact.geom.pos[1] = b[1] - normal[1] * ball_radius_;
  contact.geom.pos[2] = b[2] - normal[2] * ball_radius_;
  // Normal into body 1, the ball: pushes it away from the roller.
  for (int k = 0; k < 3; ++k) {
    contact.geom.normal[k] = normal[k];
    contact.fdir1[k] = fdir[k] / fnorm;
  }
  contact.geom.depth = std::max(0.0, touch - distance);
  contact.geom.g1 = ball.geom();
  contact.geom.g2 = drive_->chassis_geom();
  contact.surface.mode = dContactFDir1 | dContactMotion1 | dContactMu2 | dContactApprox1_2;
  // Along the roller's motion the grip is the roller motor's torque over its
  // radius; across it, ordinary friction.
  contact.surface.mu = t.dribbler_max_torque / t.dribbler_roller_radius;
  contact.surface.motion1 = command.dribbler_speed * t.dribbler_roller_radius;
  contact.surface.mu2 = physics_.ball_robot_friction;
  const dJointID joint = dJointCreateContact(world, group, &contact);
  dJointAttach(joint, ball.body(), body);
}

void Robot::fill_state(robot_state_t& out, const Ball& ball, double now) const {
  const RobotTypeConfig& t = *type_;
  const dBodyID body = drive_->chassis();
  const dReal* p = dBodyGetPosition(body);
  const dReal* q = dBodyGetQuaternion(body);
  const dReal* v = dBodyGetLinearVel(body);
  const dReal* w = dBodyGetAngularVel(body);
  const dReal* R = dBodyGetRotation(body);
  out.team = static_cast<int8_t>(team_);
  out.robot_id = id_;
  out.robot_type = t.name;
  out.x = p[0];
  out.y = p[1];
  out.orientation = heading_angle(R);
  out.vx = v[0];
  out.vy = v[1];
  out.omega = w[2];
  // The centre of mass, whichever model (the planar body sits on the floor).
  const double lift = t.center_of_mass_height - chassis_origin_height(t);
  for (int k = 0; k < 3; ++k) {
    out.body.position[k] = p[k] + R[4 * k + 2] * lift;
    out.body.linear_velocity[k] = v[k];
    out.body.angular_velocity[k] = w[k];
  }
  for (int k = 0; k < 4; ++k) out.body.orientation[k] = q[k];
  drive_->measured_wheel_speeds(wheel_speed_buffer_);
  out.num_wheels = static_cast<int32_t>(wheel_speed_buffer_.size());
  out.wheel_speeds = wheel_speed_buffer_;
  out.ball_contact = ball_at_kicker(ball);
  out.kicker_charged = kicker_charged(now);
  out.last_command_time = last_command_time_;
}

}  // namespace ubersim::physics
