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
  EXPECT_EQ(world.counters().commands_clamped.commands, 1u);
  EXPECT_EQ(world.counters().commands_clamped.text(), "1 (kick speed 1)");  // summary and ping
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

// Distance (m) from the robot's centre to the ball's, in the floor plane.
double ball_distance(const World& world, const Robot& robot) {
  const PlanarState s = robot.planar_state();
  const dReal* b = world.ball().position();
  return std::hypot(b[0] - s.x, b[1] - s.y);
}

// Spinning on the spot at 8 rad/s with the dribbler on: the roller's grip
// alone cannot hold the ball against the turn; perfect dribbling (ER-Force's
// simulate_dribbling = false) holds it where it touched the face.
TEST_P(KickerDribbler, PerfectDribblingHoldsTheBallThroughATurnSimulatedDribblingLosesIt) {
  World& world = setup_robot_and_ball(0.002);
  const double resting = robot_->type().kicker_distance + world.setup().ball.radius;
  robot_command_t c = velocity_command(7, 0, 0, 8.0);
  c.dribbler_speed = robot_->type().dribbler_max_speed / 2;

  world.set_perfect_dribbling(true);
  world.command(Team::Blue, 7, c);
  run_for(world, 1.0);
  const double held = ball_distance(world, *robot_);
  const bool held_at_face = robot_->ball_at_kicker(world.ball());
  std::printf("%s: perfect dribbling, 1 s at 8 rad/s: ball %.4f m from the centre (resting %.4f)\n",
              model_name(GetParam()), held, resting);
  EXPECT_TRUE(robot_->holds_ball());
  EXPECT_TRUE(held_at_face);
  EXPECT_NEAR(held, resting, 0.005);

  // Switched back: the same turn flings the ball off.
  world.set_perfect_dribbling(false);
  EXPECT_FALSE(robot_->holds_ball());
  run_for(world, 1.0);
  const double lost = ball_distance(world, *robot_);
  std::printf("%s: simulated dribbling, 1 s more: ball %.3f m from the centre\n",
              model_name(GetParam()), lost);
  EXPECT_FALSE(robot_->ball_at_kicker(world.ball()));
  EXPECT_GT(lost, resting + 0.05);
}

TEST_P(KickerDribbler, PerfectDribblingLetsGoForAKickAndWithTheDribblerOff) {
  World& world = setup_robot_and_ball(0.002);
  world.set_perfect_dribbling(true);
  robot_command_t c = velocity_command(7, 0, 0, 0);
  c.dribbler_speed = robot_->type().dribbler_max_speed / 2;
  world.command(Team::Blue, 7, c);
  run_for(world, 0.1);
  ASSERT_TRUE(robot_->holds_ball());
  c.kick_speed = 4.0;
  world.command(Team::Blue, 7, c);
  run_for(world, 3 * world.dt());
  EXPECT_FALSE(robot_->holds_ball());
  EXPECT_NEAR(world.ball().velocity()[0], 4.0, 0.05 * 4.0);
  // Dribbler off: nothing is held.
  World& again = setup_robot_and_ball(0.002);
  again.set_perfect_dribbling(true);
  again.command(Team::Blue, 7, velocity_command(7, 0, 0, 0));
  run_for(again, 0.1);
  EXPECT_FALSE(robot_->holds_ball());
}

// ER-Force's body: a kicker (and dribbler) set back from the flat front in a
// mouth. The ball rests against the kicker face inside the front, where the
// kicker reaches it; above the mouth the front is still there.
TEST_P(KickerDribbler, ABallRestsInTheMouthAtTheKickerDistance) {
  world_ = std::make_unique<World>(empty_world(GetParam()));
  World& world = *world_;
  world.define_robot_type("mouth", robot_config_text("omni4_ssl", GetParam(),
                                                     {{"FRONT_DISTANCE", "0.078"},
                                                      {"KICKER_DISTANCE", "0.0715"},
                                                      {"MOUTH_HEIGHT", "0.06"}}));
  robot_ = &world.add_robot(Team::Blue, 7, "mouth", PlanarState{});
  const double r = world.setup().ball.radius;
  // A ball rolling slowly into the mouth meets the kicker face, 6.5 mm
  // behind the flat front (without a mouth it would stop at the front).
  world.place_ball(0.0715 + r + 0.03, 0, 0, -0.3, 0, 0);
  double closest = 1;
  for (int i = 0; i < 240; ++i) {
    world.step();
    closest = std::min(closest, ball_distance(world, *robot_));
  }
  std::printf(
      "%s: rolling ball's closest approach %.4f m from the centre (kicker face 0.0715 + "
      "radius %.4f; front 0.078)\n",
      model_name(GetParam()), closest, r);
  EXPECT_NEAR(closest, 0.0715 + r, 0.001);
  // The dribbler holds a ball there, and the kicker kicks it from there.
  world.place_ball(0.0715 + r + 0.001, 0, 0, 0, 0, 0);
  robot_command_t c = velocity_command(7, 0, 0, 0);
  c.dribbler_speed = robot_->type().dribbler_max_speed / 2;
  world.command(Team::Blue, 7, c);
  run_for(world, 0.5);
  const double held = ball_distance(world, *robot_);
  std::printf("%s: dribbler holds it %.4f m from the centre\n", model_name(GetParam()), held);
  EXPECT_NEAR(held, 0.0715 + r, 0.002);
  EXPECT_TRUE(robot_->ball_at_kicker(world.ball()));
  c.kick_speed = 4.0;
  world.command(Team::Blue, 7, c);
  run_for(world, 3 * world.dt());
  EXPECT_NEAR(world.ball().velocity()[0], 4.0, 0.05 * 4.0);
  // Above the mouth the lip is the front: a ball overlapping it there is
  // pushed out to the flat front (in the open mouth it would stay put).
  world.place_ball(0.078 + r - 0.005, 0, 0.1, 0, 0, 0);
  run_for(world, 5 * world.dt());
  const double pushed = world.ball().position()[0] - robot_->planar_state().x;
  std::printf(
      "%s: ball overlapping the lip by 5 mm: after 5 steps %.4f m ahead (front + radius "
      "%.4f)\n",
      model_name(GetParam()), pushed, 0.078 + r);
  EXPECT_GT(pushed, 0.078 + r - 0.002);
}

INSTANTIATE_TEST_SUITE_P(BothDriveModels, KickerDribbler,
                         ::testing::Values(DriveModel::Jointed, DriveModel::Planar),
                         drive_model_test_name);

}  // namespace
}  // namespace ubersim::physics::testing
