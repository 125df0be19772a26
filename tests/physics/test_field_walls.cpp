// The walls stand where the field config puts them, measured with the ball:
// a ball rolled at a wall turns back where its surface meets the wall's inner
// face. The 2026 Division A field leaves 0.6 m behind the goal lines and 0.3 m
// along the touch lines; a field change at run time (SIM_CONTROL SET_FIELD)
// moves the walls and the goals with it, and may give the ball another radius.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "physics_test_support.hpp"

namespace ubersim::physics::testing {
namespace {

constexpr double kWallTolerance = 0.005;  // m: the ball's contact depth plus one step of travel

// Rolls the ball from (x, y) with velocity (vx, vy) for up to 3 s and returns
// the farthest its surface got along the direction of travel (the ball's
// reach: centre plus radius), after checking that it came back.
double reach_of_ball(World& world, double x, double y, double vx, double vy) {
  world.place_ball(x, y, 0, vx, vy, 0);
  const double ux = vx / std::hypot(vx, vy), uy = vy / std::hypot(vx, vy);
  const double r = world.setup().ball.radius;
  double farthest = -1e9;
  bool came_back = false;
  const double end = world.time() + 3.0;
  while (world.time() < end && !came_back) {
    world.step();
    const dReal* p = world.ball().position();
    const dReal* v = world.ball().velocity();
    farthest = std::max(farthest, p[0] * ux + p[1] * uy + r);
    came_back = v[0] * ux + v[1] * uy < -0.1;
  }
  EXPECT_TRUE(came_back) << "the ball never bounced back";
  return farthest;
}

TEST(FieldWalls, AsymmetricBoundaryWallsStandWhereConfigured) {
  World world(empty_world(DriveModel::Planar, "division_a"));
  const FieldConfig& f = world.setup().field;
  ASSERT_DOUBLE_EQ(f.boundary_width, 0.3);
  ASSERT_DOUBLE_EQ(f.boundary_width_goal_line, 0.6);

  // Along x, beside the goal (|y| = 2 m > goal_width / 2): the goal-line wall at 6 + 0.6 m.
  const double goal_line_wall = reach_of_ball(world, 5.0, 2.0, 2.0, 0);
  EXPECT_NEAR(goal_line_wall, 6.6, kWallTolerance);
  const double other_goal_line_wall = reach_of_ball(world, -5.0, -2.0, -2.0, 0) * -1;
  EXPECT_NEAR(other_goal_line_wall, -6.6, kWallTolerance);
  // Along y: the touch-line wall at 4.5 + 0.3 m.
  const double touch_line_wall = reach_of_ball(world, 1.0, 3.5, 0, 2.0);
  EXPECT_NEAR(touch_line_wall, 4.8, kWallTolerance);
  std::printf("measured walls: goal line %.4f m, %.4f m; touch line %.4f m\n", goal_line_wall,
              other_goal_line_wall, touch_line_wall);
}

TEST(FieldWalls, FieldChangeAtRunTimeMovesTheWalls) {
  World world(empty_world(DriveModel::Planar, "division_b"));
  world.change_field("BOUNDARY_WIDTH = 0.25\nBOUNDARY_WIDTH_GOAL_LINE = 0.45\n");
  const double goal_line_wall = reach_of_ball(world, 3.5, 1.5, 2.0, 0);
  EXPECT_NEAR(goal_line_wall, 4.5 + 0.45, kWallTolerance);
  const double touch_line_wall = reach_of_ball(world, 0, 2.0, 0, 2.0);
  EXPECT_NEAR(touch_line_wall, 3.0 + 0.25, kWallTolerance);
  std::printf("after the change: goal line wall %.4f m, touch line wall %.4f m\n", goal_line_wall,
              touch_line_wall);
}

// A ball dropped on the back wall of a goal comes to rest on its top: the
// goal height of a run-time field change is the height the goal is built to.
TEST(FieldWalls, GoalHeightOfAFieldChangeIsTheGoalsHeight) {
  World world(empty_world(DriveModel::Planar, "division_b"));
  world.change_field("GOAL_HEIGHT = 0.3\n");
  const FieldConfig& f = world.setup().field;
  ASSERT_DOUBLE_EQ(f.goal_height, 0.3);
  const double back_wall_x = f.field_length / 2 + f.goal_depth + f.goal_wall_thickness / 2;
  world.place_ball(back_wall_x, 0, 0.5, 0, 0, 0);
  run_for(world, 1.5);
  const double r = world.setup().ball.radius;
  const double resting = world.ball().position()[2] - r;
  EXPECT_NEAR(resting, 0.3, 0.003);
  std::printf("ball resting on the goal at %.4f m (goal height 0.3 m)\n", resting);
}

// The SSL geometry's ball radius, applied at run time: the ball rests on its
// new radius, bounces off the wall where its new surface meets it, the robots
// stay where they stood, and the announced geometry carries it.
TEST(FieldWalls, BallRadiusOfAFieldChangeIsTheBallsRadius) {
  World world(empty_world(DriveModel::Planar, "division_b"));
  PlanarState pose;
  pose.x = -1.0;
  pose.y = 0.5;
  world.add_robot(Team::Yellow, 3, "omni4_ssl", pose);
  world.change_field("BALL_RADIUS = 0.025\n");
  EXPECT_DOUBLE_EQ(world.setup().ball.radius, 0.025);
  EXPECT_DOUBLE_EQ(world.geometry().ball_radius, 0.025);
  world.place_ball(1.0, 0, 0, 0, 0, 0);
  run_for(world, 0.5);
  const double centre_height = world.ball().position()[2];
  EXPECT_NEAR(centre_height, 0.025, 0.0005);
  const double wall = reach_of_ball(world, 0, 2.0, 0, 2.0);
  EXPECT_NEAR(wall, 3.0 + 0.3, kWallTolerance);
  ASSERT_NE(world.robot(Team::Yellow, 3), nullptr);
  EXPECT_NEAR(world.robot(Team::Yellow, 3)->planar_state().x, -1.0, 0.01);
  std::printf("ball of radius 0.025 m: centre at %.4f m, touch-line wall at %.4f m\n",
              centre_height, wall);

  // A ball the robots' dribblers cannot reach (5 mm, roller 35 mm up) is
  // refused, and nothing changes.
  EXPECT_THROW(world.change_field("BALL_RADIUS = 0.005\n"), std::invalid_argument);
  EXPECT_DOUBLE_EQ(world.setup().ball.radius, 0.025);
  EXPECT_EQ(world.robots().size(), 1u);
}

}  // namespace
}  // namespace ubersim::physics::testing
