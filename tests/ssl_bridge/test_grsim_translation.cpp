// grSim's protocol, in-process: one robot command -> robot_command_t, the
// newest-command book (superseded, repeats, the stop after a silent second),
// robot status from radio feedback; and the simulation protocol's dribbler
// as the ER-Force simulator reads it.
#include <gtest/gtest.h>

#include <cmath>
#include <ubersim/team_t.hpp>

#include "ubersim/ssl_bridge/grsim_command_book.hpp"
#include "ubersim/ssl_bridge/grsim_status.hpp"
#include "ubersim/ssl_bridge/grsim_translation.hpp"
#include "ubersim/ssl_bridge/robot_control_translation.hpp"

namespace {

using namespace ubersim::ssl;
using ubersim::radio_feedback_t;
using ubersim::radio_packet_t;
using ubersim::robot_command_t;
using ubersim::robot_feedback_t;
using ubersim::sim_state_t;
using ubersim::Team;
using ubersim::team_t;
using Clock = std::chrono::steady_clock;

grSim_Robot_Command robot(uint32_t id) {
  grSim_Robot_Command c;
  c.set_id(id);
  return c;  // only the id: grSim reads every other field as unset
}

GrsimTranslationSettings settings() {
  GrsimTranslationSettings s;
  WheelMapping w;
  w.num_wheels = 4;
  w.wheel_radius = 0.03;
  w.wheel_index = {3, 2, 1, 0};  // ours: FL BL BR FR, as grSim's (FR slot -> our wheel 3)
  s.wheels = w;
  s.spinner_speed = 800;
  return s;
}

TEST(GrsimTranslation, UnsetFieldsAreZeroAndNoKick) {
  Errors errors;
  const auto c = translate_grsim_robot_command(robot(4), settings(), nullptr, errors);
  ASSERT_TRUE(c.has_value());
  EXPECT_TRUE(errors.empty());
  EXPECT_EQ(c->command.robot_id, 4);
  EXPECT_EQ(c->command.mode, int8_t{robot_command_t::MODE_LOCAL_VELOCITY});
  EXPECT_EQ(c->command.vx, 0.0);
  EXPECT_EQ(c->command.kick_speed, 0.0);
  EXPECT_EQ(c->command.chip_speed, 0.0);
  EXPECT_EQ(c->command.dribbler_speed, 0.0);
  EXPECT_EQ(c->kick, GrsimKick::None);
}

TEST(GrsimTranslation, KicksAsGrsimDoes) {
  Errors errors;
  grSim_Robot_Command in = robot(1);
  in.set_kickspeedx(0.00005f);  // below grSim's threshold: nothing
  EXPECT_EQ(translate_grsim_robot_command(in, settings(), nullptr, errors)->kick, GrsimKick::None);
  in.set_kickspeedx(6);
  auto flat = translate_grsim_robot_command(in, settings(), nullptr, errors);
  EXPECT_EQ(flat->kick, GrsimKick::Flat);
  EXPECT_DOUBLE_EQ(flat->command.kick_speed, 6);
  // A small upward speed is a chip of ubersim's, but grSim names it flat (< 1 m/s).
  in.set_kickspeedz(0.5f);
  auto low = translate_grsim_robot_command(in, settings(), nullptr, errors);
  EXPECT_EQ(low->kick, GrsimKick::Flat);
  EXPECT_NEAR(low->command.chip_speed, std::hypot(6.0, 0.5), 1e-6);
  EXPECT_NEAR(low->command.chip_angle, std::atan2(0.5, 6.0), 1e-6);
  EXPECT_EQ(low->command.kick_speed, 0.0);
  // Straight up: the steepest chip the radio takes.
  in.set_kickspeedx(0);
  in.set_kickspeedz(3);
  auto up = translate_grsim_robot_command(in, settings(), nullptr, errors);
  EXPECT_EQ(up->kick, GrsimKick::Chip);
  EXPECT_LT(up->command.chip_angle, M_PI / 2);
  EXPECT_NEAR(up->command.chip_speed, 3, 1e-6);
  EXPECT_TRUE(errors.empty());
}

TEST(GrsimTranslation, SpinnerAndNonFiniteValues) {
  Errors errors;
  grSim_Robot_Command in = robot(2);
  in.set_spinner(true);
  EXPECT_EQ(translate_grsim_robot_command(in, settings(), nullptr, errors)->command.dribbler_speed,
            800);
  in.set_veltangent(NAN);
  EXPECT_FALSE(translate_grsim_robot_command(in, settings(), nullptr, errors).has_value());
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].code(), kErrorInvalid);
}

TEST(GrsimTranslation, WheelsByGrsimsNumberingKeepingTheOnesNotGiven) {
  Errors errors;
  grSim_Robot_Command in = robot(0);
  in.set_wheelsspeed(true);
  in.set_wheel1(1);
  in.set_wheel4(4);
  auto first = translate_grsim_robot_command(in, settings(), nullptr, errors);
  // wheel1 (front left) -> FL slot -> our wheel 0; wheel4 (front right) -> our wheel 3.
  EXPECT_EQ(first->command.wheel_speeds, (std::vector<double>{1, 0, 0, 4}));
  grSim_Robot_Command next = robot(0);
  next.set_wheelsspeed(true);
  next.set_wheel3(3);
  auto second = translate_grsim_robot_command(next, settings(), &first->command, errors);
  EXPECT_EQ(second->command.wheel_speeds, (std::vector<double>{1, 0, 3, 4}));
  GrsimTranslationSettings no_wheels = settings();
  no_wheels.wheels.reset();
  EXPECT_FALSE(translate_grsim_robot_command(in, no_wheels, nullptr, errors).has_value());
  EXPECT_EQ(errors.back().code(), kErrorUnsupported);
}

TEST(GrsimTranslation, ReplacementDefaultsAsGrsims) {
  grSim_Replacement in;
  grSim_RobotReplacement* r = in.add_robots();
  r->set_id(3);
  r->set_dir(-90);
  in.add_robots()->set_id(16);  // beyond grSim's slots
  sim_state_t state{};
  state.ball.linear_velocity[0] = 0.5;
  in.mutable_ball()->set_vy(1);
  Errors errors;
  const SimulatorCommand out = grsim_replacement_command(in, &state, errors);
  ASSERT_EQ(out.control().teleport_robot_size(), 1);
  const TeleportRobot& t = out.control().teleport_robot(0);
  EXPECT_EQ(t.id().team(), BLUE);
  EXPECT_TRUE(t.present());
  EXPECT_EQ(t.x(), 0.0f);
  EXPECT_NEAR(t.orientation(), -M_PI / 2, 1e-6);
  EXPECT_EQ(errors.size(), 1u);
  EXPECT_FALSE(out.control().teleport_ball().has_x());
  EXPECT_FLOAT_EQ(out.control().teleport_ball().vx(), 0.5f);
  EXPECT_FLOAT_EQ(out.control().teleport_ball().vy(), 1.0f);
}

GrsimRobotCommand command(int id, double vx, double kick = 0, double dribbler = 0) {
  GrsimRobotCommand c;
  c.command.robot_id = id;
  c.command.vx = vx;
  c.command.kick_speed = kick;
  c.command.dribbler_speed = dribbler;
  c.kick = kick > 0 ? GrsimKick::Flat : GrsimKick::None;
  return c;
}

TEST(GrsimCommandBook, EveryRobotsNewestCommandInOnePacketAndSupersededCounted) {
  GrsimCommandBook book(std::chrono::seconds(1));
  const Clock::time_point t0{};
  book.heard(Team::Blue, t0);
  book.put(Team::Blue, command(1, 0.1), t0);
  book.put(Team::Blue, command(2, 0.2), t0);
  book.put(Team::Blue, command(1, 0.3), t0);  // replaces one not yet sent
  EXPECT_EQ(book.superseded(Team::Blue), 1u);
  ASSERT_TRUE(book.has_news(Team::Blue));
  radio_packet_t p = book.packet(Team::Blue, t0);
  EXPECT_EQ(p.team, int8_t{team_t::BLUE});
  ASSERT_EQ(p.num_commands, 2);
  EXPECT_EQ(p.commands[0].vx, 0.3);
  EXPECT_EQ(p.commands[1].vx, 0.2);
  book.put(Team::Blue, command(2, 0.4), t0);  // robot 2's last one was sent: not superseded
  EXPECT_EQ(book.superseded(Team::Blue), 1u);
  p = book.packet(Team::Blue, t0);
  EXPECT_EQ(p.num_commands, 2);  // robot 1 too, so a newer packet never loses it
  EXPECT_FALSE(book.has_news(Team::Yellow));
}

TEST(GrsimCommandBook, SilentTeamRepeatsWithoutKicksThenStopsAfterTheHold) {
  GrsimCommandBook book(std::chrono::seconds(1));
  const Clock::time_point t0{};
  const auto repeat = std::chrono::milliseconds(40);
  book.heard(Team::Yellow, t0);
  book.put(Team::Yellow, command(5, 1.0, 4.0, 300), t0);
  EXPECT_EQ(book.packet(Team::Yellow, t0).commands[0].kick_speed, 4.0);
  EXPECT_EQ(book.next_due(Team::Yellow, repeat), t0 + repeat);
  EXPECT_FALSE(book.due(Team::Yellow, t0 + std::chrono::milliseconds(39), repeat));
  const auto again = book.due(Team::Yellow, t0 + repeat, repeat);
  ASSERT_TRUE(again.has_value());
  EXPECT_EQ(again->commands[0].vx, 1.0);
  EXPECT_EQ(again->commands[0].kick_speed, 0.0);
  const auto stop = book.due(Team::Yellow, t0 + std::chrono::seconds(1), repeat);
  ASSERT_TRUE(stop.has_value());
  EXPECT_EQ(stop->commands[0].robot_id, 5);
  EXPECT_EQ(stop->commands[0].vx, 0.0);
  EXPECT_EQ(stop->commands[0].dribbler_speed, 300);  // grSim resets only the wheels
  EXPECT_EQ(book.stops(Team::Yellow), 1u);
  EXPECT_FALSE(book.due(Team::Yellow, t0 + std::chrono::seconds(5), repeat));
  EXPECT_FALSE(book.next_due(Team::Yellow, repeat));

  GrsimCommandBook for_ever(Clock::duration::zero());
  for_ever.heard(Team::Blue, t0);
  for_ever.put(Team::Blue, command(1, 1.0), t0);
  for_ever.packet(Team::Blue, t0);
  const auto late = for_ever.due(Team::Blue, t0 + std::chrono::hours(1), repeat);
  ASSERT_TRUE(late.has_value());
  EXPECT_EQ(late->commands[0].vx, 1.0);
}

TEST(GrsimCommandBook, AKickRidesOnlyInThePacketsOfItsWindow) {
  GrsimCommandBook book(std::chrono::seconds(1));
  const Clock::time_point t0{};
  book.heard(Team::Blue, t0);
  book.put(Team::Blue, command(5, 1.0, 4.0), t0);
  EXPECT_EQ(book.packet(Team::Blue, t0).commands[0].kick_speed, 4.0);
  book.put(Team::Blue, command(6, 1.0), t0 + std::chrono::milliseconds(30));
  // Within the window: a newer packet replacing the first on the radio still kicks.
  EXPECT_EQ(book.packet(Team::Blue, t0 + std::chrono::milliseconds(30)).commands[0].kick_speed,
            4.0);
  book.put(Team::Blue, command(6, 1.0), t0 + std::chrono::milliseconds(60));
  const radio_packet_t later = book.packet(Team::Blue, t0 + std::chrono::milliseconds(60));
  EXPECT_EQ(later.commands[0].robot_id, 5);
  EXPECT_EQ(later.commands[0].kick_speed, 0.0);  // grSim kicks once
  EXPECT_EQ(later.commands[0].vx, 1.0);
}

TEST(GrsimStatus, ChangesOnlyAndKicksFromTheKickerDischarging) {
  GrsimStatus status;
  auto flat = [](int32_t) { return GrsimKick::Flat; };
  radio_feedback_t f{};
  f.t_measured = 1.0;
  robot_feedback_t r{};
  r.robot_id = 2;
  r.kicker_charged = true;
  f.robots = {r};
  f.num_robots = 1;
  status.on_feedback(Team::Blue, f, flat);
  EXPECT_FALSE(status.changes(Team::Blue).has_value());  // as grSim starts: nothing to say
  f.robots[0].ball_contact = true;
  status.on_feedback(Team::Blue, f, flat);
  auto changes = status.changes(Team::Blue);
  ASSERT_TRUE(changes.has_value());
  EXPECT_TRUE(changes->robots_status(0).infrared());
  EXPECT_FALSE(status.changes(Team::Blue).has_value());  // said once
  f.t_measured = 1.05;
  f.robots[0].kicker_charged = false;
  status.on_feedback(Team::Blue, f, flat);
  changes = status.changes(Team::Blue);
  ASSERT_TRUE(changes.has_value());
  EXPECT_TRUE(changes->robots_status(0).flat_kick());
  f.t_measured = 1.05 + kGrsimKickStatusTime;
  status.on_feedback(Team::Blue, f, flat);
  changes = status.changes(Team::Blue);
  ASSERT_TRUE(changes.has_value());
  EXPECT_FALSE(changes->robots_status(0).flat_kick());
  EXPECT_FALSE(status.changes(Team::Yellow).has_value());
}

TEST(SslRobotControl, DribblerSpeedZeroOrBelowLeavesTheDribblerOffAsErForces) {
  RobotControl control;
  RobotCommand* c = control.add_robot_commands();
  c->set_id(1);
  c->set_dribbler_speed(-600.0f);
  const auto out = translate_robot_control(control, Team::Blue, std::nullopt);
  ASSERT_EQ(out.packet.num_commands, 1);
  EXPECT_EQ(out.packet.commands[0].dribbler_speed, 0.0);
}

}  // namespace
