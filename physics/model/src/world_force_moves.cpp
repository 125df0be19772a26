// Moves by force (placement mode BY_FORCE, the SSL simulation protocol's
// by_force): instead of teleporting, the ball is pushed towards its target by
// a horizontal force each step, and a robot drives itself there with its own
// motors, until another placement of that body ends it. The bodies keep
// colliding with everything on the way.
#include <algorithm>
#include <cmath>

#include "ubersim/angles.hpp"
#include "ubersim/physics/world.hpp"

namespace ubersim::physics {
namespace {

// Ball: a critically damped spring towards the target, its pull capped like
// a firm push (about 1 s to cross a few metres, no overshoot).
constexpr double kBallNaturalFrequency = 4.0;  // rad/s
constexpr double kBallMaxAcceleration = 6.0;   // m/s^2
// Robot: velocity towards the target proportional to the distance left,
// within the robot type's own limits.
constexpr double kRobotGain = 2.5;            // 1/s
constexpr double kRobotTurnGain = 4.0;        // 1/s
constexpr double kRobotCommandTimeout = 0.1;  // s, so it stops if the moves end abruptly

}  // namespace

void World::apply_force_moves() {
  if (ball_force_) {
    dBodyID body = ball_->body();
    const dReal* p = dBodyGetPosition(body);
    const dReal* v = dBodyGetLinearVel(body);
    const double w = kBallNaturalFrequency;
    double ax = w * w * (ball_force_->x - p[0]) - 2 * w * v[0];
    double ay = w * w * (ball_force_->y - p[1]) - 2 * w * v[1];
    const double a = std::hypot(ax, ay);
    if (a > kBallMaxAcceleration) {
      ax *= kBallMaxAcceleration / a;
      ay *= kBallMaxAcceleration / a;
    }
    dBodyAddForce(body, setup_.ball.mass * ax, setup_.ball.mass * ay, 0);
  }
  for (auto it = robot_force_.begin(); it != robot_force_.end();) {
    const Team team = static_cast<Team>(it->first.first);
    Robot* r = robot(team, it->first.second);
    if (r == nullptr) {
      it = robot_force_.erase(it);
      continue;
    }
    const PlanarState s = r->planar_state();
    const RobotTypeConfig& type = r->type();
    robot_command_t command{};
    command.robot_id = it->first.second;
    command.mode = robot_command_t::MODE_GLOBAL_VELOCITY;
    double vx = kRobotGain * (it->second.x - s.x);
    double vy = kRobotGain * (it->second.y - s.y);
    const double speed = std::hypot(vx, vy);
    if (speed > type.max_speed) {
      vx *= type.max_speed / speed;
      vy *= type.max_speed / speed;
    }
    command.vx = vx;
    command.vy = vy;
    command.omega = std::clamp(kRobotTurnGain * wrap_angle(it->second.orientation - s.heading),
                               -type.max_angular_speed, type.max_angular_speed);
    apply_command(team, it->first.second, command, kRobotCommandTimeout);
    ++it;
  }
}

}  // namespace ubersim::physics
