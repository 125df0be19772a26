#pragma once
// The ball: an ODE sphere whose carpet behaviour comes from its config.
//
// A ball kicked without spin slides, friction spinning it up, until it rolls;
// then only rolling resistance slows it. Both phases are ODE contact
// physics here, with the parameters derived so that the published numbers
// hold: the friction coefficient gives the sliding deceleration, the moment
// of inertia gives the speed where sliding turns to rolling, and ODE's
// rolling friction gives the rolling deceleration.
#include "ubersim/physics/ball_config.hpp"
#include "ubersim/physics/geom_tag.hpp"
#include "ubersim/physics/ode_handles.hpp"

namespace ubersim::physics {

struct BallSurface {
  double ground_friction = 0;   // Coulomb coefficient against the carpet (unitless)
  double rolling_friction = 0;  // ODE rho: rolling resistance torque / normal force (m)
  double inertia_factor = 0;    // k in I = k m r^2 (unitless)
};

// Derivation (sphere of radius r, I = k m r^2, carpet friction mu, rolling
// resistance torque rho N, which also acts while sliding):
//   sliding:    dv/dt = -mu g,  r dw/dt = g (mu - rho / r) / k
//   rolling at: v = q v0  with  q = slide_to_roll_ratio
//   rolling:    dv/dt = -rho g / (r (1 + k))
// Solving for mu, k and rho gives the values below.
BallSurface derive_ball_surface(const BallConfig& ball, double gravity);

class Ball {
 public:
  Ball(dWorldID world, dSpaceID space, const BallConfig& config, const BallSurface& surface);
  Ball(const Ball&) = delete;
  Ball& operator=(const Ball&) = delete;

  dBodyID body() const { return body_.get(); }
  dGeomID geom() const { return geom_.get(); }
  const BallConfig& config() const { return config_; }
  const BallSurface& surface() const { return surface_; }

  // Puts the ball at a position with a velocity and no spin.
  void place(const double position[3], const double velocity[3]);
  const dReal* position() const { return dBodyGetPosition(body_.get()); }
  const dReal* velocity() const { return dBodyGetLinearVel(body_.get()); }

 private:
  BallConfig config_;
  BallSurface surface_;
  BodyHandle body_;
  GeomHandle geom_;
  GeomTag tag_{GeomKind::Ball};
};

}  // namespace ubersim::physics
