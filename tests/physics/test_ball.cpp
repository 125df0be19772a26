// The ball against its configuration: a ball started at 3 m/s without spin
// slides at the configured deceleration, starts rolling at the configured
// fraction of its start speed, then rolls at the configured deceleration;
// a chipped ball bounces keeping the configured share of its vertical speed.
#include <gtest/gtest.h>

#include <cstdio>

#include "physics_test_support.hpp"

namespace ubersim::physics::testing {
namespace {

struct Phases {
  double sliding_deceleration = 0;
  double switch_ratio = 0;  // speed when it starts rolling / start speed
  double rolling_deceleration = 0;
};

Phases roll_ball(double start_speed, double direction) {
  // The large field: the ball rolls about 5.6 m, centred on the field's middle.
  World world(empty_world(DriveModel::Planar, "division_a"));
  const BallConfig& b = world.setup().ball;
  const double c = std::cos(direction), s = std::sin(direction);
  world.place_ball(-2.8 * c, -2.8 * s, 0, start_speed * c, start_speed * s, 0);
  Phases p;
  double t_switch = -1;
  std::vector<std::pair<double, double>> speeds;  // (t, v)
  while (world.time() < 4.0) {
    world.step();
    const dReal* v = world.ball().velocity();
    const dReal* w = dBodyGetAngularVel(world.ball().body());
    // Velocity of the ball's contact point: v + w x (0, 0, -r).
    const double slip = std::hypot(v[0] - w[1] * b.radius, v[1] + w[0] * b.radius);
    const double speed = std::hypot(v[0], v[1]);
    speeds.emplace_back(world.time(), speed);
    if (t_switch < 0 && slip < 0.01 * speed) {
      t_switch = world.time();
      p.switch_ratio = speed / start_speed;
    }
  }
  auto speed_at = [&](double t) {
    for (const auto& [time, v] : speeds) {
      if (time >= t) return v;
    }
    return speeds.back().second;
  };
  // Well inside each phase: the first 80 % of sliding, 1 s to 3 s of rolling.
  const double t1 = 0.1 * t_switch, t2 = 0.8 * t_switch;
  p.sliding_deceleration = (speed_at(t1) - speed_at(t2)) / (t2 - t1);
  p.rolling_deceleration = (speed_at(t_switch + 1.0) - speed_at(t_switch + 3.0)) / 2.0;
  return p;
}

TEST(Ball, SlidesThenRollsAsConfigured) {
  const BallConfig b = load_ball_config(kConfigDir, "ssl_golf_ball");
  for (double direction : {0.0, 0.7, 2.5}) {
    SCOPED_TRACE(direction);
    const Phases p = roll_ball(3.0, direction);
    std::printf(
        "direction %.1f rad: sliding %.3f m/s^2, rolls from %.3f of the start speed, "
        "rolling %.3f m/s^2\n",
        direction, p.sliding_deceleration, p.switch_ratio, p.rolling_deceleration);
    EXPECT_NEAR(p.sliding_deceleration, b.sliding_deceleration, 0.05 * b.sliding_deceleration);
    EXPECT_NEAR(p.switch_ratio, b.slide_to_roll_ratio, 0.05 * b.slide_to_roll_ratio);
    EXPECT_NEAR(p.rolling_deceleration, b.rolling_deceleration, 0.05 * b.rolling_deceleration);
  }
}

TEST(Ball, ComesToRestAndStays) {
  World world(empty_world(DriveModel::Planar));
  world.place_ball(0, 0, 0, 1.0, 0, 0);
  run_for(world, 6.0);
  EXPECT_LT(ball_speed(world), 1e-3);
  const double x = world.ball().position()[0];
  run_for(world, 2.0);
  EXPECT_NEAR(world.ball().position()[0], x, 1e-4);
  EXPECT_NEAR(world.ball().position()[2], world.setup().ball.radius, 1e-3);
}

TEST(Ball, BouncesKeepingTheConfiguredVerticalSpeed) {
  World world(empty_world(DriveModel::Planar));
  const BallConfig& b = world.setup().ball;
  world.place_ball(0, 0, 0.5, 0, 0, 0);
  double last_vz = 0;
  std::vector<double> impacts, rebounds;
  while (world.time() < 1.5 && rebounds.size() < 2) {
    world.step();
    const double vz = world.ball().velocity()[2];
    if (last_vz < -0.5 && vz > 0) {
      impacts.push_back(-last_vz);
      rebounds.push_back(vz);
    }
    last_vz = vz;
  }
  ASSERT_EQ(rebounds.size(), 2u);
  for (std::size_t i = 0; i < rebounds.size(); ++i) {
    // The impact speed is sampled up to one step (g dt) before the impact.
    const double impact = impacts[i] + world.setup().physics.gravity * world.dt() / 2;
    EXPECT_NEAR(rebounds[i] / impact, b.bounce_restitution, 0.05 * b.bounce_restitution);
  }
}

TEST(Ball, BouncesOffWallsWithTheirRestitution) {
  World world(empty_world(DriveModel::Planar));
  const double wall = world.setup().field.half_width_to_wall();
  world.place_ball(0, wall - 0.3, 0, 0, 2.0, 0);
  double before = 0, after = 0;
  double last_vy = 2.0;
  while (world.time() < 1.0) {
    world.step();
    const double vy = world.ball().velocity()[1];
    if (last_vy > 0.5 && vy < 0) {
      before = last_vy;
      after = -vy;
      break;
    }
    last_vy = vy;
  }
  ASSERT_GT(before, 0);
  EXPECT_NEAR(after / before, world.setup().field.wall_restitution, 0.1);
  EXPECT_LT(world.ball().position()[1], wall);
}

TEST(BallSurface, DerivedParametersReproduceTheConfiguredNumbers) {
  BallConfig b = load_ball_config(kConfigDir, "ssl_golf_ball");
  const double g = 9.81;
  const BallSurface s = derive_ball_surface(b, g);
  const double r = b.radius, k = s.inertia_factor, mu = s.ground_friction;
  EXPECT_NEAR(mu * g, b.sliding_deceleration, 1e-12);
  // Rolling: rho g / (r (1 + k)).
  EXPECT_NEAR(s.rolling_friction * g / (r * (1 + k)), b.rolling_deceleration, 1e-12);
  // Start of rolling at q v0: v0 - mu g t = (g (mu - rho / r) / k) t.
  const double t_per_v0 = 1 / (mu * g + g * (mu - s.rolling_friction / r) / k);
  EXPECT_NEAR(1 - mu * g * t_per_v0, b.slide_to_roll_ratio, 1e-12);
  EXPECT_GT(k, 0);
  EXPECT_LT(k, 1);
}

}  // namespace
}  // namespace ubersim::physics::testing
