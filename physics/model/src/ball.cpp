#include "ubersim/physics/ball.hpp"

namespace ubersim::physics {

BallSurface derive_ball_surface(const BallConfig& ball, double gravity) {
  BallSurface s;
  s.ground_friction = ball.sliding_deceleration / gravity;
  // With c = (1 - q) / (mu q) and a = rolling deceleration / g:
  //   k = c (mu - a) / (1 + c a),   rho = a r (1 + k).
  const double q = ball.slide_to_roll_ratio;
  const double mu = s.ground_friction;
  const double a = ball.rolling_deceleration / gravity;
  const double c = (1 - q) / (mu * q);
  s.inertia_factor = c * (mu - a) / (1 + c * a);
  s.rolling_friction = a * ball.radius * (1 + s.inertia_factor);
  return s;
}

Ball::Ball(dWorldID world, dSpaceID space, const BallConfig& config, const BallSurface& surface)
    : config_(config), surface_(surface), body_(dBodyCreate(world)) {
  dMass mass;
  const double inertia = surface.inertia_factor * config.mass * config.radius * config.radius;
  dMassSetParameters(&mass, config.mass, 0, 0, 0, inertia, inertia, inertia, 0, 0, 0);
  dBodySetMass(body_.get(), &mass);
  geom_.reset(dCreateSphere(space, config.radius));
  dGeomSetBody(geom_.get(), body_.get());
  tag_geom(geom_.get(), &tag_);
}

void Ball::place(const double position[3], const double velocity[3]) {
  dBodySetPosition(body_.get(), position[0], position[1], position[2]);
  const dQuaternion identity = {1, 0, 0, 0};
  dBodySetQuaternion(body_.get(), identity);
  dBodySetLinearVel(body_.get(), velocity[0], velocity[1], velocity[2]);
  dBodySetAngularVel(body_.get(), 0, 0, 0);
  dBodySetForce(body_.get(), 0, 0, 0);
  dBodySetTorque(body_.get(), 0, 0, 0);
}

}  // namespace ubersim::physics
