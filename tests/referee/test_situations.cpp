// The referee's placement solver and game situations, checked against the
// rule distances on the shipped Division B field.
#include <gtest/gtest.h>

#include <cmath>

#include "ubersim/field_config.hpp"
#include "ubersim/referee/placement.hpp"
#include "ubersim/referee/situations.hpp"

using namespace ubersim;
using namespace ubersim::referee;

namespace {

field_geometry_t division_b() {
  return load_field_config(UBERSIM_SOURCE_CONFIG_DIR, "division_b").to_message(0.0215);
}

field_geometry_t division_a() {
  return load_field_config(UBERSIM_SOURCE_CONFIG_DIR, "division_a").to_message(0.0215);
}

// The official game controller's penalty mark, written out from
// ssl-game-controller internal/app/statemachine/placementPos.go (penaltyKick,
// commit 78a9b3bbbc06d1869f37d57923f2106418f2572e): x = field_length / 2 -
// PenaltyKickDistToGoal, negated when the team in favour is on the positive half.
double gc_penalty_x(double field_length, double penalty_kick_dist_to_goal,
                    bool team_in_favour_on_positive_half) {
  double x = field_length / 2.0 - penalty_kick_dist_to_goal;
  if (team_in_favour_on_positive_half) x *= -1;
  return x;
}

// 2 x 6 robots scattered deliberately badly: some on the ball, some on each other.
PlacementScene messy_scene() {
  PlacementScene scene;
  scene.ball_x = 0.3;
  scene.ball_y = -0.2;
  for (int i = 0; i < 6; ++i) {
    for (Team team : kTeams) {
      PlacedRobot r;
      r.team = team;
      r.id = i;
      r.x = (i % 3) * 0.05 + (team == Team::Blue ? 0.02 : 0.0);
      r.y = (i / 3) * 0.05 - 0.2;
      scene.robots.push_back(r);
    }
  }
  return scene;
}

double distance_to_ball(const PlacementScene& s, const PlacedRobot& r) {
  return std::hypot(r.x - s.ball_x, r.y - s.ball_y);
}

const PlacedRobot* find(const PlacementScene& s, Team team, int id) {
  for (const auto& r : s.robots) {
    if (r.team == team && r.id == id) return &r;
  }
  return nullptr;
}

}  // namespace

TEST(Placement, SeparatesAPileAndKeepsFixedRobotsStill) {
  auto scene = messy_scene();
  const PlacementBounds bounds{4.8, 3.3};
  EXPECT_FALSE(is_legal(scene, bounds));
  scene.robots[0].fixed = true;
  scene.robots[0].x = 1.0;
  scene.robots[0].y = 1.0;
  ASSERT_TRUE(separate(scene, bounds));
  EXPECT_TRUE(is_legal(scene, bounds));
  EXPECT_DOUBLE_EQ(scene.robots[0].x, 1.0);
  EXPECT_DOUBLE_EQ(scene.robots[0].y, 1.0);
}

TEST(Placement, StaysInsideTheWalls) {
  PlacementScene scene;
  scene.ball_x = 4.7;
  scene.ball_y = 3.2;
  PlacedRobot r;
  r.x = 4.75;
  r.y = 3.25;
  r.ball_keep_out = 0.6;
  scene.robots.push_back(r);
  const PlacementBounds bounds{4.8, 3.3};
  ASSERT_TRUE(separate(scene, bounds));
  EXPECT_LE(std::abs(scene.robots[0].x), 4.8 - 0.09 + 1e-9);
  EXPECT_GE(distance_to_ball(scene, scene.robots[0]), 0.6);
}

TEST(Placement, IsDeterministic) {
  auto a = messy_scene();
  auto b = messy_scene();
  const PlacementBounds bounds{4.8, 3.3};
  separate(a, bounds);
  separate(b, bounds);
  for (std::size_t i = 0; i < a.robots.size(); ++i) {
    EXPECT_EQ(a.robots[i].x, b.robots[i].x);
    EXPECT_EQ(a.robots[i].y, b.robots[i].y);
  }
}

TEST(Situations, StopKeepsEveryRobotHalfAMetreFromTheBall) {
  const auto field = division_b();
  const auto planned =
      plan_situation({Situation::Stop, Team::Yellow, 0, 0}, messy_scene(), field, {});
  EXPECT_TRUE(is_legal(planned, bounds_of(field)));
  EXPECT_DOUBLE_EQ(planned.ball_x, 0.3);  // stop leaves the ball where it is
  for (const auto& r : planned.robots)
    EXPECT_GE(distance_to_ball(planned, r), 0.5 + r.radius - 1e-6);
}

TEST(Situations, KickOffPutsTeamsInTheirHalvesAndDefendersOutsideTheCircle) {
  const auto field = division_b();
  const auto planned =
      plan_situation({Situation::KickOff, Team::Blue, 0, 0}, messy_scene(), field, {});
  EXPECT_TRUE(is_legal(planned, bounds_of(field)));
  EXPECT_EQ(planned.ball_x, 0.0);
  EXPECT_EQ(planned.ball_y, 0.0);
  int kickers = 0;
  for (const auto& r : planned.robots) {
    if (r.team == Team::Yellow) {
      EXPECT_LE(r.x, -r.radius + 1e-6);  // yellow defends negative x
      EXPECT_GE(distance_to_ball(planned, r), field.center_circle_radius + r.radius - 1e-6);
    } else {
      EXPECT_GE(r.x, r.radius - 1e-6);
      if (distance_to_ball(planned, r) < 0.2) {
        ++kickers;
        EXPECT_NEAR(std::abs(r.orientation), M_PI, 1e-9);  // facing the yellow goal
      }
    }
  }
  EXPECT_EQ(kickers, 1);
}

TEST(Situations, FreeKickClearsOpponentsAndPutsAKickerBehindTheBall) {
  const auto field = division_b();
  // Ball asked for outside the field: it is brought 0.2 m inside the lines.
  const auto planned =
      plan_situation({Situation::FreeKick, Team::Yellow, 10.0, -1.0}, messy_scene(), field, {});
  EXPECT_TRUE(is_legal(planned, bounds_of(field)));
  EXPECT_DOUBLE_EQ(planned.ball_x, field.field_length / 2 - 0.2);
  EXPECT_DOUBLE_EQ(planned.ball_y, -1.0);
  for (const auto& r : planned.robots) {
    if (r.team == Team::Blue) {
      EXPECT_GE(distance_to_ball(planned, r), 0.5 + r.radius - 1e-6);
    }
  }
  // Some yellow robot stands right behind the ball, facing the blue goal (+x).
  bool kicker = false;
  for (const auto& r : planned.robots) {
    if (r.team != Team::Yellow || distance_to_ball(planned, r) > 0.2) continue;
    const double to_goal = std::atan2(-planned.ball_y, field.field_length / 2 - planned.ball_x);
    EXPECT_NEAR(r.orientation, to_goal, 1e-9);
    EXPECT_LT(r.x, planned.ball_x);
    kicker = true;
  }
  EXPECT_TRUE(kicker);
}

TEST(Situations, PenaltyPutsKeeperOnLineAndOthersBehindTheBall) {
  const auto field = division_b();
  const auto planned =
      plan_situation({Situation::Penalty, Team::Yellow, 0, 0}, messy_scene(), field, {});
  EXPECT_TRUE(is_legal(planned, bounds_of(field)));
  const double goal_x = field.field_length / 2;  // yellow attacks +x
  EXPECT_DOUBLE_EQ(planned.ball_x, -1.5);        // 6 m from the goal attacked, in yellow's half
  int keepers = 0, kickers = 0;
  for (const auto& r : planned.robots) {
    if (r.team == Team::Blue && std::abs(r.x - (goal_x - r.radius)) < 1e-9 && r.y == 0) {
      ++keepers;
    } else if (r.team == Team::Yellow && distance_to_ball(planned, r) < 0.2) {
      ++kickers;
    } else {
      EXPECT_LE(r.x, planned.ball_x - 1.0 - r.radius + 1e-6) << team_name(r.team) << r.id;
    }
  }
  EXPECT_EQ(keepers, 1);
  EXPECT_EQ(kickers, 1);
}

// The official GC continues a penalty only with the declared goalkeeper in
// the goal: a request that names it puts that robot there, not the nearest.
TEST(Situations, PenaltyPutsTheNamedKeeperInTheGoal) {
  const auto field = division_b();
  for (int keeper : {0, 4}) {
    SituationRequest request{Situation::Penalty, Team::Yellow, 0, 0, keeper};
    const auto planned = plan_situation(request, messy_scene(), field, {});
    const PlacedRobot* in_goal = find(planned, Team::Blue, keeper);
    ASSERT_NE(in_goal, nullptr);
    EXPECT_DOUBLE_EQ(in_goal->x, field.field_length / 2 - in_goal->radius) << keeper;
    EXPECT_DOUBLE_EQ(in_goal->y, 0) << keeper;
  }
}

// Where the official GC puts the ball, for both divisions, both teams and both sides.
TEST(Situations, PenaltyMarkIsWhereTheOfficialGameControllerPutsTheBall) {
  struct Case {
    field_geometry_t field;
    double dist_to_goal;  // the GC's PenaltyKickDistToGoal for the division (config.go)
  };
  for (const Case& c : {Case{division_a(), 8.0}, Case{division_b(), 6.0}}) {
    for (int yellow_defends : {-1, 1}) {
      for (Team kicking : kTeams) {
        const FieldSides sides{yellow_defends};
        const bool on_positive_half = sides.defends(kicking) > 0;
        const double expected =
            gc_penalty_x(c.field.field_length, c.dist_to_goal, on_positive_half);
        SCOPED_TRACE(c.field.name + " " + team_name(kicking) + " defends " +
                     std::to_string(sides.defends(kicking)));
        EXPECT_DOUBLE_EQ(penalty_mark_x(c.field, sides, kicking), expected);
        const auto planned =
            plan_situation({Situation::Penalty, kicking, 0, 0}, messy_scene(), c.field, sides);
        EXPECT_DOUBLE_EQ(planned.ball_x, expected);
        EXPECT_DOUBLE_EQ(planned.ball_y, 0.0);
        EXPECT_TRUE(is_legal(planned, bounds_of(c.field)));
      }
    }
  }
  // Division A: 2 m into the kicking team's own half.
  EXPECT_DOUBLE_EQ(penalty_mark_x(division_a(), {}, Team::Yellow), -2.0);
}

// Robots may stand behind the goal lines as far as the wider boundary there.
TEST(Situations, PlacementBoundsFollowTheAsymmetricBoundary) {
  const PlacementBounds a = bounds_of(division_a());
  EXPECT_DOUBLE_EQ(a.half_length, 6.0 + 0.6);
  EXPECT_DOUBLE_EQ(a.half_width, 4.5 + 0.3);
}

TEST(Situations, BallPlacementMovesTheBallAndClearsAround) {
  const auto field = division_b();
  const auto planned = plan_situation({Situation::BallPlacement, Team::Yellow, 0.05, -0.15},
                                      messy_scene(), field, {});
  EXPECT_DOUBLE_EQ(planned.ball_x, 0.05);
  EXPECT_DOUBLE_EQ(planned.ball_y, -0.15);
  for (const auto& r : planned.robots)
    EXPECT_GE(distance_to_ball(planned, r), 0.5 + r.radius - 1e-6);
}

TEST(Situations, KickOffWithoutKickingRobotsIsAClearError) {
  auto scene = messy_scene();
  scene.robots.erase(std::remove_if(scene.robots.begin(), scene.robots.end(),
                                    [](const auto& r) { return r.team == Team::Blue; }),
                     scene.robots.end());
  EXPECT_THROW(plan_situation({Situation::KickOff, Team::Blue, 0, 0}, scene, division_b(), {}),
               std::runtime_error);
  EXPECT_NE(find(scene, Team::Yellow, 0), nullptr);
}
