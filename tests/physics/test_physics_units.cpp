// Unit tests of the physics' small parts: kinematics, chassis geometry,
// command checks, pacing schedule and config loading.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "physics_test_support.hpp"
#include "ubersim/physics/pacer.hpp"

namespace ubersim::physics::testing {
namespace {

TEST(Kinematics, InverseAndForwardAgreeForEveryShippedRobot) {
  for (const char* name : {"omni4_ssl", "omni3_cmdragons02", "omni4_ssl_planar"}) {
    SCOPED_TRACE(name);
    const WheelKinematics k(load_robot_config(kConfigDir, name));
    for (const Eigen::Vector3d& v : {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0),
                                     Eigen::Vector3d(0, 0, 3), Eigen::Vector3d(0.7, -1.2, 2)}) {
      EXPECT_TRUE(k.velocity(k.wheel_speeds(v)).isApprox(v, 1e-9));
    }
  }
}

TEST(Kinematics, FourWheelRowsFollowTheWheelGeometry) {
  const RobotTypeConfig t = load_robot_config(kConfigDir, "omni4_ssl");
  const WheelKinematics k(t);
  ASSERT_EQ(k.wheel_count(), 4u);
  // Pure rotation: every wheel turns at omega * distance / radius.
  const Eigen::VectorXd w = k.wheel_speeds(Eigen::Vector3d(0, 0, 2));
  for (Eigen::Index i = 0; i < 4; ++i) EXPECT_NEAR(w(i), 2 * 0.078 / t.wheel_radius, 1e-9);
  // Forward: wheel i contributes -sin(angle) / radius.
  const Eigen::VectorXd f = k.wheel_speeds(Eigen::Vector3d(1, 0, 0));
  for (Eigen::Index i = 0; i < 4; ++i) {
    EXPECT_NEAR(f(i), -std::sin(t.wheels[static_cast<std::size_t>(i)].angle) / t.wheel_radius,
                1e-9);
  }
}

TEST(Kinematics, DifferentialDriveCannotGoSideways) {
  const WheelKinematics k(load_robot_config(kConfigDir, "diff_drive_cmdragons02"));
  EXPECT_TRUE(k.wheel_speeds(Eigen::Vector3d(0, 1, 0)).isZero(1e-12));
  // Its best fit to any wheel speeds has no sideways part.
  EXPECT_NEAR(k.velocity(Eigen::Vector2d(3, 7)).y(), 0, 1e-12);
  const Eigen::Vector3d v(1, 0, 2);
  EXPECT_TRUE(k.velocity(k.wheel_speeds(v)).isApprox(v, 1e-9));
}

TEST(ChassisOutline, IsTheSslShape) {
  const auto o = ChassisOutline::make(0.09, 0.075, 24, 0.0, 0.15);
  EXPECT_EQ(o.vertices.size(), 25u);
  Vec2 closest, normal;
  // The flat front at x = 0.075.
  EXPECT_NEAR(o.signed_distance({0.1, 0}, &closest, &normal), 0.025, 1e-9);
  EXPECT_NEAR(normal.x, 1, 1e-9);
  EXPECT_NEAR(o.signed_distance({0.07, 0}, &closest, &normal), -0.005, 1e-9);
  // The round back, within the polygon's sagitta.
  EXPECT_NEAR(o.signed_distance({-0.2, 0}, &closest, &normal), 0.11, 0.001);
  EXPECT_NEAR(o.signed_distance({0, 0}, &closest, &normal), -0.075, 1e-9);  // nearest: the front
}

TEST(PolygonCollision, FindsDepthAndNormalOfOverlappingSquares) {
  const std::vector<Vec2> n = {{0, -1}, {1, 0}, {0, 1}, {-1, 0}};
  const std::vector<Vec2> a = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  std::vector<Vec2> b = {{0.9, 0.2}, {1.9, 0.2}, {1.9, 1.2}, {0.9, 1.2}};
  PolygonContact c;
  ASSERT_TRUE(collide_polygons(a, n, b, n, &c));
  EXPECT_NEAR(c.normal.x, 1, 1e-9);
  EXPECT_EQ(c.count, 2);
  for (int i = 0; i < c.count; ++i) EXPECT_NEAR(c.depths[i], 0.1, 1e-9);
  for (auto& v : b) v.x += 0.2;  // now apart
  EXPECT_FALSE(collide_polygons(a, n, b, n, &c));
}

TEST(ChassisGeom, CollidesWithSpheresBoxesPlanesAndOtherChassis) {
  ensure_ode_initialised();
  SpaceHandle space = make_simple_space(nullptr);
  const auto o = ChassisOutline::make(0.09, 0.075, 24, -0.04, 0.1);
  GeomHandle a(create_chassis_geom(space.get(), &o));
  dGeomSetPosition(a.get(), 0, 0, 0.045);
  dContactGeom contacts[8];
  // A ball touching the front face.
  GeomHandle ball(dCreateSphere(nullptr, 0.0215));
  dGeomSetPosition(ball.get(), 0.075 + 0.02, 0, 0.0215);
  ASSERT_EQ(dCollide(a.get(), ball.get(), 8, contacts, sizeof(dContactGeom)), 1);
  EXPECT_NEAR(contacts[0].depth, 0.0015, 1e-9);
  EXPECT_NEAR(contacts[0].normal[0], -1, 1e-9);  // into the chassis (g1)
  // Reversed order: ODE flips it for us.
  ASSERT_EQ(dCollide(ball.get(), a.get(), 8, contacts, sizeof(dContactGeom)), 1);
  EXPECT_NEAR(contacts[0].normal[0], 1, 1e-9);
  // A ball whose centre is inside is pushed out through the nearest face.
  dGeomSetPosition(ball.get(), 0.07, 0, 0.0215);
  ASSERT_EQ(dCollide(a.get(), ball.get(), 8, contacts, sizeof(dContactGeom)), 1);
  EXPECT_NEAR(contacts[0].depth, 0.005 + 0.0215, 1e-9);
  // Far away: nothing.
  dGeomSetPosition(ball.get(), 0.5, 0, 0.0215);
  EXPECT_EQ(dCollide(a.get(), ball.get(), 8, contacts, sizeof(dContactGeom)), 0);
  // A wall box 1 cm into the back.
  GeomHandle wall(dCreateBox(nullptr, 0.05, 1, 0.1));
  dGeomSetPosition(wall.get(), -0.09 - 0.025 + 0.01, 0, 0.05);
  auto deepest = [&](int count) {
    double d = 0;
    for (int i = 0; i < count; ++i) d = std::max(d, contacts[i].depth);
    return d;
  };
  const int n = dCollide(a.get(), wall.get(), 8, contacts, sizeof(dContactGeom));
  ASSERT_GE(n, 1);
  EXPECT_NEAR(contacts[0].normal[0], 1, 0.05);
  EXPECT_NEAR(deepest(n), 0.01, 1e-6);
  // The floor: an upright chassis above it does not touch; one sunk in does.
  GeomHandle floor(dCreatePlane(nullptr, 0, 0, 1, 0));
  EXPECT_EQ(dCollide(a.get(), floor.get(), 8, contacts, sizeof(dContactGeom)), 0);
  dGeomSetPosition(a.get(), 0, 0, 0.03);
  EXPECT_EQ(dCollide(a.get(), floor.get(), 4, contacts, sizeof(dContactGeom)), 4);
  EXPECT_NEAR(contacts[0].depth, 0.01, 1e-9);
  // Another chassis, back to back, 1 cm into this one.
  GeomHandle b(create_chassis_geom(space.get(), &o));
  dGeomSetPosition(a.get(), 0, 0, 0.045);
  dGeomSetPosition(b.get(), -0.17, 0, 0.045);
  dMatrix3 turned;
  dRFromAxisAndAngle(turned, 0, 0, 1, M_PI);
  dGeomSetRotation(b.get(), turned);
  int m = dCollide(a.get(), b.get(), 8, contacts, sizeof(dContactGeom));
  ASSERT_GE(m, 1);
  EXPECT_NEAR(contacts[0].normal[0], 1, 0.1);
  EXPECT_NEAR(deepest(m), 0.01, 1e-4);  // tip on tip: along an edge normal 6 deg off
  // Its flat front against this one's back: 5 mm.
  dGeomSetRotation(b.get(), dGeomGetRotation(a.get()));
  dGeomSetPosition(b.get(), -0.16, 0, 0.045);
  m = dCollide(a.get(), b.get(), 8, contacts, sizeof(dContactGeom));
  ASSERT_GE(m, 1);
  EXPECT_NEAR(deepest(m), 0.005, 1e-6);
}

TEST(CommandCheck, ClampsAndDrops) {
  const RobotTypeConfig t = load_robot_config(kConfigDir, "omni4_ssl");
  robot_command_t c = velocity_command(0, 10, 0, 100);
  c.kick_speed = 10;
  c.chip_angle = 2;  // rad: beyond the robot's maximum
  CommandCheck check = check_command(c, t);
  ASSERT_TRUE(check.accepted);
  EXPECT_TRUE(check.clamped);
  EXPECT_DOUBLE_EQ(check.command.vx, t.max_speed);
  EXPECT_DOUBLE_EQ(check.command.omega, t.max_angular_speed);
  EXPECT_DOUBLE_EQ(check.command.kick_speed, t.kick_max_speed);
  EXPECT_DOUBLE_EQ(check.command.chip_angle, t.chip_max_angle);
  c = velocity_command(0, 1, 0, 0);
  check = check_command(c, t);
  EXPECT_FALSE(check.clamped);
  EXPECT_DOUBLE_EQ(check.command.chip_angle, t.chip_default_angle);
  c.vy = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(check_command(c, t).accepted);
  // A robot without a chip kicker does not chip.
  const RobotTypeConfig omni3 = load_robot_config(kConfigDir, "omni3_cmdragons02");
  c = velocity_command(0, 0, 0, 0);
  c.chip_speed = 3;
  check = check_command(c, omni3);
  EXPECT_TRUE(check.clamped);
  EXPECT_EQ(check.command.chip_speed, 0.0);
}

// Physics drops exactly what the check every part shares finds
// (ubersim/command_check.hpp), and applies everything else, clamped.
TEST(CommandCheck, DropsWhatTheSharedCheckFinds) {
  const RobotTypeConfig t = load_robot_config(kConfigDir, "omni4_ssl");
  const auto wheels = [](std::vector<double> speeds) {
    robot_command_t c = velocity_command(0, 0, 0, 0);
    c.mode = robot_command_t::MODE_WHEEL_SPEEDS;
    c.num_wheels = static_cast<std::int32_t>(speeds.size());
    c.wheel_speeds = std::move(speeds);
    return c;
  };
  robot_command_t unknown_mode = velocity_command(0, 1, 0, 0);
  unknown_mode.mode = 7;
  robot_command_t nan_speed = velocity_command(0, std::nan(""), 0, 0);
  robot_command_t count_mismatch = wheels({1, 2, 3, 4});
  count_mismatch.num_wheels = 3;
  robot_command_t unread_nan_wheel = velocity_command(0, 1, 0, 0);
  unread_nan_wheel.wheel_speeds = {std::nan("")};
  unread_nan_wheel.num_wheels = 1;
  const std::vector<std::pair<robot_command_t, bool>> cases{
      {unknown_mode, false},
      {nan_speed, false},
      {wheels({1, 2, 3}), false},
      {wheels({1, std::nan(""), 3, 4}), false},
      {count_mismatch, false},
      {wheels({1e6, 2, 3, 4}), true},
      {velocity_command(0, 1e6, 0, 0), true},
      {unread_nan_wheel, true}};
  for (const auto& [command, accepted] : cases) {
    EXPECT_EQ(check_command(command, t).accepted, accepted);
    EXPECT_EQ(!find_command_fault(command, t.wheels.size(), nullptr).has_value(), accepted);
  }
}

TEST(Pacer, FollowsAnAbsoluteScheduleWithoutDrift) {
  using Clock = Pacer::Clock;
  const double dt = 1.0 / 240;
  Pacer pacer(dt, 1.0, 0.25);
  const Clock::time_point t0{};
  pacer.restart(t0, 0);
  // Step n ends at sim time (n + 1) dt and is due then, however late earlier steps ran.
  EXPECT_EQ(pacer.due(0),
            t0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(dt)));
  const auto due_a_minute = pacer.due(60 * 240 - 1);
  EXPECT_NEAR(std::chrono::duration<double>(due_a_minute - t0).count(), 60.0, 1e-6);
  EXPECT_NEAR(pacer.drift(due_a_minute, 60 * 240), 0.0, 1e-6);
  // Twice real time: half the wall time.
  pacer.set_speed(2.0, t0, 0);
  EXPECT_NEAR(std::chrono::duration<double>(pacer.due(239) - t0).count(), 0.5, 1e-6);
  // Far behind: the schedule restarts instead of racing to catch up.
  EXPECT_FALSE(pacer.restart_if_behind(pacer.due(10) + std::chrono::milliseconds(100), 10));
  EXPECT_TRUE(pacer.restart_if_behind(pacer.due(10) + std::chrono::seconds(1), 10));
  pacer.set_speed(0, t0, 0);
  EXPECT_TRUE(pacer.as_fast_as_possible());
  pacer.set_speed(-1, t0, 0);
  EXPECT_TRUE(pacer.lockstep());
}

TEST(PhysicsConfigs, LoadAndRejectBadValues) {
  const PhysicsConfig p = load_physics_config(kConfigDir, "default");
  EXPECT_DOUBLE_EQ(p.step_rate, 240);
  EXPECT_EQ(p.solver, Solver::QuickStep);
  EXPECT_EQ(p.solver_iterations, 10);
  const BallConfig b = load_ball_config(kConfigDir, "ssl_golf_ball");
  EXPECT_DOUBLE_EQ(b.radius, 0.0215);
  auto bad = ConfigFile::parse(
      "RADIUS = 0.0215\nMASS = 0.046\nSLIDING_DECELERATION = 0.2\nROLLING_DECELERATION = 0.3\n"
      "SLIDE_TO_ROLL_RATIO = 0.7\nBOUNCE_RESTITUTION = 0.5\nROBOT_RESTITUTION = 0.5\n",
      "b.cfg");
  try {
    load_ball_config(bad, "b");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("b.cfg:4: ROLLING_DECELERATION"), std::string::npos)
        << e.what();
  }
}

TEST(RobotConfigs, NewKeysAreCheckedWithFileAndLine) {
  const RobotTypeConfig t = load_robot_config(kConfigDir, "omni4_ssl");
  EXPECT_GT(t.ground_clearance, 0);
  EXPECT_GT(t.kicker_reach, 0);
  EXPECT_GE(t.chip_max_angle, t.chip_default_angle);
  const RobotTypeConfig d = load_robot_config(kConfigDir, "diff_drive_cmdragons02");
  EXPECT_GT(d.caster_radius, 0);
  // A kicker wider than the flat front is an error naming the key.
  const auto base = ConfigFile::load(kConfigDir + "/robots/omni4_ssl.cfg");
  auto text = std::string("BASE = ") + kConfigDir + "/robots/omni4_ssl.cfg\nKICKER_WIDTH = 0.15\n";
  try {
    load_robot_config(ConfigFile::parse(text, "wide.cfg"), "wide");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("wide.cfg:2: KICKER_WIDTH"), std::string::npos)
        << e.what();
  }
}

// The optional keys: braking limits and a kicker set back into a mouth.
TEST(RobotConfigs, OptionalBrakeAndMouthKeysAreCheckedWithFileAndLine) {
  const std::string base = std::string("BASE = ") + kConfigDir + "/robots/omni4_ssl.cfg\n";
  const auto error_of = [](const std::string& text) {
    try {
      load_robot_config(ConfigFile::parse(text, "t.cfg"), "t");
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const RobotTypeConfig t = load_robot_config(
      ConfigFile::parse(base + "MAX_BRAKE_ACCELERATION = 5.5\nKICKER_DISTANCE = 0.07\n"
                               "MOUTH_HEIGHT = 0.06\n",
                        "t.cfg"),
      "t");
  EXPECT_DOUBLE_EQ(t.max_brake_acceleration, 5.5);
  EXPECT_DOUBLE_EQ(t.max_angular_brake_acceleration, t.max_angular_acceleration);
  EXPECT_DOUBLE_EQ(t.kicker_distance, 0.07);
  EXPECT_TRUE(t.has_mouth());
  EXPECT_NE(
      error_of(base + "MAX_BRAKE_ACCELERATION = -1\n").find("t.cfg:2: MAX_BRAKE_ACCELERATION"),
      std::string::npos);
  EXPECT_NE(error_of(base + "MAX_ANGULAR_BRAKE_ACCELERATION = nan\n")
                .find("t.cfg:2: MAX_ANGULAR_BRAKE_ACCELERATION"),
            std::string::npos);
  // Beyond the flat front, or a mouth without its height.
  EXPECT_NE(error_of(base + "KICKER_DISTANCE = 0.08\n").find("t.cfg:2: KICKER_DISTANCE"),
            std::string::npos);
  const std::string no_height = error_of(base + "KICKER_DISTANCE = 0.07\n");
  EXPECT_NE(no_height.find("t.cfg:2: KICKER_DISTANCE"), std::string::npos) << no_height;
  EXPECT_NE(no_height.find("MOUTH_HEIGHT"), std::string::npos) << no_height;
  EXPECT_NE(
      error_of(base + "KICKER_DISTANCE = 0.07\nMOUTH_HEIGHT = 0.5\n").find("t.cfg:3: MOUTH_HEIGHT"),
      std::string::npos);
}

}  // namespace
}  // namespace ubersim::physics::testing
