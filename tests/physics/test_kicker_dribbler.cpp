// Kicker and dribbler, for both drive models: a flat kick leaves at the
// commanded speed, a chip lands where its speed and angle say, the kicker
// fires only with the ball on its face and only when charged, and the
// dribbler spins the ball backwards and pulls it along.
#include <gtest/gtest.h>

#include <cstdio>

#include "physics_test_support.hpp"

namespace ubersim::physics::testing {
namespace {

class KickerDribbler : public ::testing::TestWithParam<DriveModel> {
 protected:
  // A robot at the origin facing +x with the ball resting against its front,
  // given a few steps to settle.
  World& setup_robot_and_ball(double gap = 0.0) {
    world_ = std::make_unique<World>(empty_world(GetParam()));
    robot_ = &world_->add_robot(Team::Blue, 7, "omni4_ssl", PlanarState{});
    const double x = robot_->type().front_distance + world_->setup().ball.radius + gap;
    world_->place_ball(x, 0, 0, 0, 0, 0);
    run_for(*world_, 0.1);
    return *world_;
  }

  robot_command_t kick(double speed, double chip_speed = 0, double chip_angle = 0) const {
    robot_command_t c = velocity_command(7, 0, 0, 0);
    c.kick_speed = speed;
    c.chip_speed = chip_speed;
    c.chip_angle = chip_angle;
    return c;
  }

  std::unique_ptr<World> world_;
  Robot* robot_ = nullptr;
};

TEST_P(KickerDribbler, FlatKickLeavesAtTheCommandedSpeed) {
  World& world = setup_robot_and_ball();
  const double speed = robot_->type().kick_max_speed;
  ASSERT_TRUE(robot_->ball_at_kicker(world.ball()));
  world.command(Team::Blue, 7, kick(speed));
  run_for(world, 3 * world.dt());
  const dReal* v = world.ball().velocity();
  std::printf("%s: flat kick at %.2f m/s leaves at %.3f m/s\n", model_name(GetParam()), speed,
              std::hypot(v[0], v[1]));
  EXPECT_NEAR(v[0], speed, 0.05 * speed);
  EXPECT_NEAR(v[1], 0, 0.05);
  EXPECT_NEAR(v[2], 0, 0.05);
  EXPECT_EQ(world.counters().kicks, 1u);
  // The robot takes the reaction without being thrown about.
  const PlanarState s = robot_->planar_state();
  EXPECT_LT(std::abs(s.vx), 0.5);
  EXPECT_GT(robot_->uprightness(), std::cos(0.05));
}

TEST_P(KickerDribbler, OverLimitKickIsClampedToTheRobotsMaximum) {
  World& world = setup_robot_and_ball();
  world.command(Team::Blue, 7, kick(50.0));
  run_for(world, 3 * world.dt());
  const double max = robot_->type().kick_max_speed;
  EXPECT_NEAR(world.ball().velocity()[0], max, 0.05 * max);
  EXPECT_EQ(world.counters().commands_clamped, 1u);
}

TEST_P(KickerDribbler, ChipLandsAtTheBallisticDistance) {
  World& world = setup_robot_and_ball();
  const double speed = 4.0, angle = 45 * M_PI / 180;
  const double start_x = world.ball().position()[0];
  world.command(Team::Blue, 7, kick(0, speed, angle));
  double last_vz = 0;
  double landing_x = -1;
  bool airborne = false;
  while (world.time() < 3.0 && landing_x < 0) {
    world.step();
    const double vz = world.ball().velocity()[2];
    if (vz > 1.0) airborne = true;
    if (airborne && last_vz < -1.0 && vz > last_vz + 1.0) landing_x = world.ball().position()[0];
    last_vz = vz;
  }
  const double expected = speed * speed * std::sin(2 * angle) / world.setup().physics.gravity;
  std::printf("%s: chip at %.1f m/s, 45 deg lands %.3f m away (ballistic %.3f m)\n",
              model_name(GetParam()), speed, landing_x - start_x, expected);
  ASSERT_GT(landing_x, 0);
  EXPECT_NEAR(landing_x - start_x, expected, 0.1 * expected);
}

TEST_P(KickerDribbler, KicksOnlyWithTheBallOnTheFace) {
  World& world = setup_robot_and_ball(0.05);  // 5 cm in front
  EXPECT_FALSE(robot_->ball_at_kicker(world.ball()));
  world.command(Team::Blue, 7, kick(5.0));
  run_for(world, 0.3);
  EXPECT_LT(ball_speed(world), 0.01);
  EXPECT_EQ(world.counters().kicks, 0u);
  // Beside the face (behind the robot) it does not fire either.
  world.place_ball(-robot_->type().radius - world.setup().ball.radius, 0, 0, 0, 0, 0);
  run_for(world, 0.3);
  EXPECT_EQ(world.counters().kicks, 0u);
}

TEST_P(KickerDribbler, RechargesBeforeTheNextKick) {
  World& world = setup_robot_and_ball();
  const double recharge = robot_->type().kicker_recharge_time;
  world.command(Team::Blue, 7, kick(2.0));
  world.step();
  EXPECT_EQ(world.counters().kicks, 1u);
  sim_state_t state;
  world.fill_state(state);
  EXPECT_FALSE(state.robots[0].kicker_charged);
  // Ball straight back onto the face: the armed kicker must wait.
  const double x = robot_->type().front_distance + world.setup().ball.radius;
  world.place_ball(x, 0, 0, 0, 0, 0);
  run_for(world, recharge / 2);
  EXPECT_EQ(world.counters().kicks, 1u);
  world.place_ball(x, 0, 0, 0, 0, 0);
  run_for(world, recharge / 2 + 2 * world.dt());
  EXPECT_EQ(world.counters().kicks, 2u);
}

TEST_P(KickerDribbler, DribblerSpinsTheBallBackAndPullsItAlong) {
  World& world = setup_robot_and_ball(0.002);
  robot_command_t c = velocity_command(7, 0, 0, 0);
  c.dribbler_speed = robot_->type().dribbler_max_speed / 2;
  world.command(Team::Blue, 7, c);
  run_for(world, 0.3);
  // Backspin: for a robot facing +x the ball turns about -y (rolls towards it).
  EXPECT_LT(dBodyGetAngularVel(world.ball().body())[1], -10.0);
  EXPECT_TRUE(robot_->ball_at_kicker(world.ball()));
  sim_state_t state;
  world.fill_state(state);
  EXPECT_TRUE(state.robots[0].ball_contact);
  // Backing away slowly, the robot keeps the ball at its front.
  c.vx = -0.5;
  world.command(Team::Blue, 7, c);
  run_for(world, 1.0);
  const double gap = world.ball().position()[0] - robot_->planar_state().x;
  EXPECT_LT(gap, robot_->type().front_distance + world.setup().ball.radius + 0.02);
  EXPECT_LT(robot_->planar_state().x, -0.3);
}

TEST_P(KickerDribbler, WithoutDribblerTheBallStaysBehind) {
  World& world = setup_robot_and_ball(0.002);
  world.command(Team::Blue, 7, velocity_command(7, -0.5, 0, 0));
  run_for(world, 1.0);
  const double gap = world.ball().position()[0] - robot_->planar_state().x;
  EXPECT_GT(gap, robot_->type().front_distance + world.setup().ball.radius + 0.2);
}

INSTANTIATE_TEST_SUITE_P(BothDriveModels, KickerDribbler,
                         ::testing::Values(DriveModel::Jointed, DriveModel::Planar),
                         drive_model_test_name);

}  // namespace
}  // namespace ubersim::physics::testing
