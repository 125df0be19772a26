// Collisions, for both drive models: a 6.5 m/s ball never passes through a
// robot or a wall, robots driven into each other collide without passing
// through, and in a busy game nothing leaves the field.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <random>

#include "physics_test_support.hpp"

namespace ubersim::physics::testing {
namespace {

class Collisions : public ::testing::TestWithParam<DriveModel> {};

// Ball centre relative to the robot's outline (2D, m): < 0 means inside.
double ball_to_outline(const Robot& robot, const Ball& ball) {
  const PlanarState s = robot.planar_state();
  const dReal* b = ball.position();
  const double c = std::cos(s.heading), sn = std::sin(s.heading);
  const Vec2 local{c * (b[0] - s.x) + sn * (b[1] - s.y), -sn * (b[0] - s.x) + c * (b[1] - s.y)};
  Vec2 closest, normal;
  return robot.outline().signed_distance(local, &closest, &normal);
}

// `slack`: how far past a wall's face a centre may be caught for one step.
bool inside_walls(const World& world, double x, double y, double slack = 0) {
  return std::abs(x) <= world.setup().field.half_length_to_wall() + slack &&
         std::abs(y) <= world.setup().field.half_width_to_wall() + slack;
}

// How deep two robots' outlines overlap (m), 0 when apart.
double overlap(const Robot& a, const Robot& b) {
  auto outline = [](const Robot& r, std::vector<Vec2>& v, std::vector<Vec2>& n) {
    const PlanarState s = r.planar_state();
    const double c = std::cos(s.heading), sn = std::sin(s.heading);
    for (std::size_t i = 0; i < r.outline().vertices.size(); ++i) {
      v.push_back(Vec2{s.x, s.y} + rotate(r.outline().vertices[i], c, sn));
      n.push_back(rotate(r.outline().normals[i], c, sn));
    }
  };
  std::vector<Vec2> av, an, bv, bn;
  outline(a, av, an);
  outline(b, bv, bn);
  PolygonContact contact;
  if (!collide_polygons(av, an, bv, bn, &contact)) return 0;
  return std::max(contact.depths[0], contact.count > 1 ? contact.depths[1] : 0.0);
}

TEST_P(Collisions, FastBallNeverPassesThroughARobot) {
  for (int heading_deg = 0; heading_deg < 360; heading_deg += 45) {
    for (int approach_deg = 0; approach_deg < 360; approach_deg += 30) {
      SCOPED_TRACE("robot heading " + std::to_string(heading_deg) + " deg, ball from " +
                   std::to_string(approach_deg) + " deg");
      World world(empty_world(GetParam()));
      PlanarState pose;
      pose.heading = heading_deg * M_PI / 180;
      const Robot& robot = world.add_robot(Team::Yellow, 0, "omni4_ssl", pose);
      const double a = approach_deg * M_PI / 180;
      // From 1 m away, aimed 2 cm off centre, at the SSL's top kick speed.
      const double speed = 6.5;
      world.place_ball(std::cos(a) - 0.02 * std::sin(a), std::sin(a) + 0.02 * std::cos(a), 0,
                       -speed * std::cos(a), -speed * std::sin(a), 0);
      // In one step the ball moves speed * dt; its centre can be caught at
      // most that far past its surface, for one step, and is then pushed out.
      const double worst = speed * world.dt() - world.setup().ball.radius;
      double min_distance = 1e9;
      int steps_inside = 0;
      for (int i = 0; i < 120; ++i) {
        world.step();
        const double d = ball_to_outline(robot, world.ball());
        min_distance = std::min(min_distance, d);
        steps_inside = d < 0 ? steps_inside + 1 : 0;
        ASSERT_LE(steps_inside, 1) << "ball inside the robot for two steps at step " << i;
      }
      EXPECT_GT(min_distance, -worst);
      EXPECT_GT(ball_to_outline(robot, world.ball()), 0.0);
      // ... and it is back on the side it came from.
      const dReal* b = world.ball().position();
      EXPECT_GT(b[0] * std::cos(a) + b[1] * std::sin(a), 0.0);
    }
  }
}

TEST_P(Collisions, FastBallNeverPassesThroughAWall) {
  World world(empty_world(GetParam()));
  const FieldConfig& f = world.setup().field;
  // At every wall and into both goals, square on and at a slant.
  struct Shot {
    double x, y, vx, vy;
  };
  const double hx = f.half_length_to_wall(), hy = f.half_width_to_wall();
  const std::vector<Shot> shots = {{hx - 0.5, 0.5, 6.5, 0},
                                   {-hx + 0.5, -0.8, -6.5, 0},
                                   {0, hy - 0.5, 0, 6.5},
                                   {1, -hy + 0.5, 3.0, -5.76},
                                   {hx - 0.6, hy - 0.6, 4.6, 4.6},
                                   {f.field_length / 2 - 0.5, 0, 6.5, 0.3},
                                   {-f.field_length / 2 + 0.5, 0.1, -6.5, -0.5},
                                   {f.field_length / 2 - 0.2, 0, 2.0, 6.2}};
  // A 6.5 m/s centre can be caught this far past the face of a wall, for a step.
  const double slack = 6.5 * world.dt() - world.setup().ball.radius;
  for (const Shot& shot : shots) {
    SCOPED_TRACE("shot from (" + std::to_string(shot.x) + ", " + std::to_string(shot.y) + ")");
    world.place_ball(shot.x, shot.y, 0, shot.vx, shot.vy, 0);
    for (int i = 0; i < 240; ++i) {
      world.step();
      const dReal* b = world.ball().position();
      ASSERT_TRUE(inside_walls(world, b[0], b[1], slack)) << "at step " << i;
      // In a goal it stays in the goal: never through its back wall.
      if (std::abs(b[0]) > f.field_length / 2 && std::abs(b[1]) < f.goal_width / 2) {
        ASSERT_LT(std::abs(b[0]), f.field_length / 2 + f.goal_depth + slack) << "at step " << i;
      }
    }
    const dReal* b = world.ball().position();
    EXPECT_TRUE(inside_walls(world, b[0], b[1], -world.setup().ball.radius + 1e-3));
  }
  EXPECT_EQ(world.counters().bodies_reset, 0u);
}

TEST_P(Collisions, RobotsDrivenIntoEachOtherDoNotPassThrough) {
  // Head on (round backs, then flat fronts) and at an angle.
  for (const double heading : {0.0, M_PI, M_PI / 3}) {
    SCOPED_TRACE("heading " + std::to_string(heading));
    World world(empty_world(GetParam()));
    PlanarState left, right;
    left.x = -0.5;
    left.heading = heading;
    right.x = 0.5;
    right.heading = heading + M_PI;
    Robot& a = world.add_robot(Team::Yellow, 0, "omni4_ssl", left);
    Robot& b = world.add_robot(Team::Blue, 0, "omni4_ssl", right);
    robot_command_t towards = velocity_command(0, 2.0, 0, 0);
    towards.mode = robot_command_t::MODE_GLOBAL_VELOCITY;
    world.command(Team::Yellow, 0, towards);
    towards.vx = -2.0;
    world.command(Team::Blue, 0, towards);
    double deepest = 0;
    double closest = 1e9;
    for (int i = 0; i < 2 * 240; ++i) {
      world.step();
      const PlanarState sa = a.planar_state(), sb = b.planar_state();
      closest = std::min(closest, std::hypot(sa.x - sb.x, sa.y - sb.y));
      deepest = std::max(deepest, overlap(a, b));
    }
    std::printf("%s, heading %.2f rad: robots pushing at full power overlap at most %.1f mm\n",
                model_name(GetParam()), heading, deepest * 1000);
    // They met, and pushing with all their motors sank into each other no
    // more than 1.5 cm (of an 18 cm robot): no passing through.
    EXPECT_LT(closest, 2 * a.type().radius);
    EXPECT_LT(deepest, 0.015);
    EXPECT_GT(a.uprightness(), std::cos(0.1));
    EXPECT_GT(b.uprightness(), std::cos(0.1));
    EXPECT_EQ(world.counters().bodies_reset, 0u);
  }
}

TEST_P(Collisions, RobotDrivenIntoAWallStaysInside) {
  World world(empty_world(GetParam()));
  PlanarState pose;
  pose.x = 3.5;
  pose.y = 2.5;
  Robot& robot = world.add_robot(Team::Yellow, 1, "omni4_ssl", pose);
  robot_command_t c = velocity_command(1, 2.5, 2.5, 1.0);
  c.mode = robot_command_t::MODE_GLOBAL_VELOCITY;
  world.command(Team::Yellow, 1, c);
  const FieldConfig& f = world.setup().field;
  // Contacts are found once a step: a robot at its top speed may be one step
  // of travel into the wall before it is pushed back (planar model into the
  // goal-line wall after sliding along the touch line: 11.0 mm).
  const double slack =
      robot.type().max_speed * world.dt() + world.setup().physics.contact_surface_layer;
  double deepest = -1;
  for (int i = 0; i < 3 * 240; ++i) {
    world.step();
    const PlanarState s = robot.planar_state();
    ASSERT_LE(s.x + robot.type().radius, f.half_length_to_wall() + slack) << "step " << i;
    ASSERT_LE(s.y + robot.type().radius, f.half_width_to_wall() + slack) << "step " << i;
    deepest = std::max({deepest, s.x + robot.type().radius - f.half_length_to_wall(),
                        s.y + robot.type().radius - f.half_width_to_wall()});
  }
  std::printf("%s: deepest into a wall %.2f mm (one step at top speed: %.2f mm)\n",
              model_name(GetParam()), deepest * 1000, slack * 1000);
  EXPECT_EQ(world.counters().bodies_reset, 0u);
}

TEST_P(Collisions, NothingLeavesTheFieldInABusyGame) {
  WorldSetup setup = load_world_setup(kConfigDir, "division_b_6v6", "default");
  setup.robot_types = types_with_model(GetParam());
  World world(setup);
  std::mt19937 random(42);
  std::uniform_real_distribution<double> unit(-1, 1);
  const FieldConfig& f = world.setup().field;
  for (int i = 0; i < 8 * 240; ++i) {
    if (i % 60 == 0) {
      // Every quarter second, every robot gets a new random command, kicks included.
      for (const auto& r : world.robots()) {
        robot_command_t c =
            velocity_command(r->id(), 3.0 * unit(random), 3.0 * unit(random), 8.0 * unit(random));
        c.mode = robot_command_t::MODE_GLOBAL_VELOCITY;
        c.kick_speed = unit(random) > -0.5 ? 6.5 : 0;
        // Chips stay below the walls (1.5 m/s at 45 deg rises 6 cm): a ball that
        // flies over them leaves the field legitimately (see the test below).
        c.chip_speed = unit(random) > 0.7 ? 1.5 : 0;
        c.dribbler_speed = unit(random) > 0 ? 800 : 0;
        world.command(r->team(), r->id(), c);
      }
      // Every second, the ball onto some robot's kicker: kicks and chips fly.
      if (i % 240 == 0) {
        const auto& r = *world.robots()[static_cast<std::size_t>(i / 240) % world.robots().size()];
        const PlanarState s = r.planar_state();
        const double reach = r.type().front_distance + world.setup().ball.radius;
        world.place_ball(s.x + reach * std::cos(s.heading), s.y + reach * std::sin(s.heading), 0, 0,
                         0, 0);
      }
    }
    world.step();
    const dReal* b = world.ball().position();
    ASSERT_TRUE(inside_walls(world, b[0], b[1])) << "ball at step " << i;
    ASSERT_GT(b[2], 0.0);
    for (const auto& r : world.robots()) {
      const PlanarState s = r->planar_state();
      ASSERT_TRUE(std::abs(s.x) < f.half_length_to_wall() && std::abs(s.y) < f.half_width_to_wall())
          << team_name(r->team()) << " " << r->id() << " at step " << i;
    }
  }
  EXPECT_EQ(world.counters().bodies_reset, 0u);
  EXPECT_GT(world.counters().kicks, 0u);
}

TEST_P(Collisions, BallChippedOverTheWallComesBackInside) {
  World world(empty_world(GetParam()));
  const FieldConfig& f = world.setup().field;
  PlanarState pose;
  pose.x = f.half_length_to_wall() - 1.0;
  const Robot& robot = world.add_robot(Team::Yellow, 3, "omni4_ssl", pose);
  world.place_ball(pose.x + robot.type().front_distance + world.setup().ball.radius, 0, 0, 0, 0, 0);
  robot_command_t chip = velocity_command(3, 0, 0, 0);
  chip.chip_speed = 5.0;
  world.command(Team::Yellow, 3, chip);
  run_for(world, 1.0);
  EXPECT_EQ(world.counters().bodies_reset, 1u);
  const dReal* b = world.ball().position();
  EXPECT_TRUE(inside_walls(world, b[0], b[1], -world.setup().ball.radius + 1e-6));
  EXPECT_GT(b[0], f.field_length / 2 - 1.0);  // back where it left, not at the centre
}

INSTANTIATE_TEST_SUITE_P(BothDriveModels, Collisions,
                         ::testing::Values(DriveModel::Jointed, DriveModel::Planar),
                         drive_model_test_name);

}  // namespace
}  // namespace ubersim::physics::testing
