// RobotSpecs -> robot types defined at run time, in-process: the produced
// config text is read back by the same reader physics uses.
#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>
#include <ssl_simulation_custom_erforce_robot_spec.pb.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <ubersim/team_t.hpp>

#include "ubersim/config_paths.hpp"
#include "ubersim/robot_type_definition.hpp"
#include "ubersim/ssl_bridge/sim_control_translation.hpp"

using namespace ubersim;
using namespace ubersim::ssl;

namespace {

BaseRobotType omni4() {
  const std::string dir = UBERSIM_SOURCE_CONFIG_DIR;
  const RobotTypeConfig config = load_robot_config(dir, "omni4_ssl");
  return base_robot_type(ConfigFile::load(resolve_config(dir, "robots", "omni4_ssl")), config,
                         0.0215);
}

bool mentions(const Errors& errors, const std::string& code, const std::string& text) {
  for (const auto& e : errors) {
    if (e.code() == code && e.message().find(text) != std::string::npos) return true;
  }
  return false;
}

}  // namespace

TEST(SslRobotSpecs, EveryHonouredFieldReachesTheRobotType) {
  const BaseRobotType base = omni4();
  google::protobuf::RepeatedPtrField<RobotSpecs> all;
  RobotSpecs& specs = *all.Add();
  specs.mutable_id()->set_id(4);
  specs.mutable_id()->set_team(BLUE);
  specs.set_radius(0.08f);
  specs.set_height(0.14f);
  specs.set_mass(2.0f);
  specs.set_max_linear_kick_speed(4.0f);
  specs.set_max_chip_kick_speed(3.0f);
  specs.set_center_to_dribbler(0.07f);
  specs.mutable_limits()->set_acc_speedup_absolute_max(2.5f);
  specs.mutable_limits()->set_acc_brake_absolute_max(3.5f);
  specs.mutable_limits()->set_acc_speedup_angular_max(30.f);
  specs.mutable_limits()->set_acc_brake_angular_max(45.f);
  specs.mutable_limits()->set_vel_absolute_max(2.0f);
  specs.mutable_limits()->set_vel_angular_max(8.0f);
  RobotWheelAngles* w = specs.mutable_wheel_angles();
  w->set_front_right(static_cast<float>(60 * M_PI / 180));
  w->set_back_right(static_cast<float>(135 * M_PI / 180));
  w->set_back_left(static_cast<float>(225 * M_PI / 180));
  w->set_front_left(static_cast<float>(300 * M_PI / 180));
  RobotSpecErForce erforce;
  erforce.set_dribbler_width(0.06f);
  erforce.set_shoot_radius(0.064f);
  specs.add_custom()->PackFrom(erforce);

  const RobotSpecsTranslation out = translate_robot_specs(all, base);
  for (const auto& e : out.errors) ADD_FAILURE() << e.code() << ": " << e.message();
  ASSERT_EQ(out.types.size(), 1u);
  const DefinedRobotType& type = out.types[0];
  EXPECT_EQ(type.name, "ssl_specs_blue_4");
  EXPECT_EQ(type.team, +team_t::BLUE);
  ASSERT_TRUE(type.robot_id);
  EXPECT_EQ(*type.robot_id, 4);
  const RobotTypeConfig read = parse_robot_type_definition(type.name, type.config_text);
  EXPECT_NEAR(read.radius, 0.08, 1e-6);
  EXPECT_NEAR(type.radius, 0.08, 1e-6);
  EXPECT_NEAR(read.height, 0.14, 1e-6);
  EXPECT_NEAR(read.mass, 2.0, 1e-6);
  EXPECT_NEAR(read.kick_max_speed, 4.0, 1e-6);
  EXPECT_NEAR(read.chip_max_speed, 3.0, 1e-6);
  EXPECT_NEAR(read.front_distance, 0.07, 1e-6);
  // ER-Force's body: the flat front at center_to_dribbler, the ball resting
  // against the dribbler at shoot_radius, in a mouth between them.
  EXPECT_NEAR(read.kicker_distance, 0.064, 1e-6);
  EXPECT_TRUE(read.has_mouth());
  EXPECT_NEAR(read.mouth_height, 0.06, 1e-6);
  EXPECT_NEAR(read.max_acceleration, 2.5, 1e-6);
  EXPECT_NEAR(read.max_angular_acceleration, 30, 1e-5);
  EXPECT_NEAR(read.max_brake_acceleration, 3.5, 1e-6);
  EXPECT_NEAR(read.max_angular_brake_acceleration, 45, 1e-5);
  EXPECT_NEAR(read.max_speed, 2.0, 1e-6);
  EXPECT_NEAR(read.max_angular_speed, 8.0, 1e-6);
  EXPECT_NEAR(read.dribbler_width, 0.06, 1e-6);
  EXPECT_NEAR(read.kicker_width, 0.06, 1e-6);
  // Clockwise 300 deg (front left) is counter-clockwise 60 deg, and so on.
  ASSERT_EQ(read.wheels.size(), 4u);
  const double expected_deg[] = {60, 135, 225, 300};
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(read.wheels[i].angle * 180 / M_PI, expected_deg[i], 1e-4) << i;
    EXPECT_NEAR(read.wheels[i].distance, base.config.wheels[0].distance * 0.08 / 0.09, 1e-6);
  }
  // Inertia follows mass and radius squared.
  EXPECT_NEAR(
      read.moment_of_inertia,
      base.config.moment_of_inertia * (2.0 / base.config.mass) * (0.08 / 0.09) * (0.08 / 0.09),
      1e-9);
}

TEST(SslRobotSpecs, FieldsThatCannotBeHonouredAreNamedInErrors) {
  const BaseRobotType base = omni4();
  google::protobuf::RepeatedPtrField<RobotSpecs> all;
  RobotSpecs& specs = *all.Add();
  specs.mutable_id()->set_team(YELLOW);  // no id: the whole team
  specs.set_mass(-1.0f);
  specs.mutable_limits()->set_acc_brake_absolute_max(std::nanf(""));
  specs.mutable_limits()->set_acc_brake_angular_max(-5.0f);
  google::protobuf::Any other;
  other.set_type_url("type.googleapis.com/SomeoneElsesSpec");
  *specs.add_custom() = other;
  google::protobuf::Any broken;
  broken.set_type_url("type.googleapis.com/RobotSpecErForce");
  broken.set_value("\xff\xff\xff");
  *specs.add_custom() = broken;
  RobotSpecs& no_team = *all.Add();
  no_team.mutable_id()->set_id(1);

  const RobotSpecsTranslation out = translate_robot_specs(all, base);
  EXPECT_TRUE(mentions(out.errors, kErrorInvalid, "robot_specs[0].mass"));
  EXPECT_TRUE(mentions(out.errors, kErrorInvalid, "robot_specs[0].limits.acc_brake_absolute_max"));
  EXPECT_TRUE(mentions(out.errors, kErrorInvalid, "robot_specs[0].limits.acc_brake_angular_max"));
  EXPECT_TRUE(mentions(out.errors, kErrorUnsupported, "robot_specs[0].custom[0]"));
  EXPECT_TRUE(mentions(out.errors, kErrorMalformed, "robot_specs[0].custom[1]"));
  EXPECT_TRUE(mentions(out.errors, kErrorInvalid, "robot_specs[1].id.team"));
  ASSERT_EQ(out.types.size(), 1u);  // the yellow team's still applies, without the bad fields
  EXPECT_EQ(out.types[0].name, "ssl_specs_yellow");
  EXPECT_FALSE(out.types[0].robot_id);
  const RobotTypeConfig read =
      parse_robot_type_definition(out.types[0].name, out.types[0].config_text);
  EXPECT_NEAR(read.mass, base.config.mass, 1e-9);
  EXPECT_NEAR(read.radius, 0.09, 1e-6);  // the protocol's default radius
  // The bad brake limits are not applied: the type brakes as it speeds up.
  EXPECT_EQ(read.max_brake_acceleration, base.config.max_acceleration);
  EXPECT_EQ(read.max_angular_brake_acceleration, base.config.max_angular_acceleration);
}

TEST(SslRobotSpecs, AnInvalidShootRadiusIsNamedAndTheFrontStays) {
  google::protobuf::RepeatedPtrField<RobotSpecs> all;
  RobotSpecs& specs = *all.Add();
  specs.mutable_id()->set_team(BLUE);
  specs.set_center_to_dribbler(0.075f);
  RobotSpecErForce erforce;
  erforce.set_shoot_radius(-0.07f);
  erforce.set_dribbler_width(std::nanf(""));
  specs.add_custom()->PackFrom(erforce);
  const RobotSpecsTranslation out = translate_robot_specs(all, omni4());
  EXPECT_TRUE(mentions(out.errors, kErrorInvalid, "robot_specs[0].custom[0].shoot_radius"));
  EXPECT_TRUE(mentions(out.errors, kErrorInvalid, "robot_specs[0].custom[0].dribbler_width"));
  ASSERT_EQ(out.types.size(), 1u);
  const RobotTypeConfig read =
      parse_robot_type_definition(out.types[0].name, out.types[0].config_text);
  EXPECT_FALSE(read.has_mouth());
  EXPECT_NEAR(read.kicker_distance, 0.075, 1e-6);
}

// A dribbler reaching out beyond the hull (shoot_radius beyond
// center_to_dribbler) is not an error: the ball rests on the flat front.
TEST(SslRobotSpecs, AShootRadiusBeyondTheFrontPutsTheKickerAtTheFront) {
  google::protobuf::RepeatedPtrField<RobotSpecs> all;
  RobotSpecs& specs = *all.Add();
  specs.mutable_id()->set_team(YELLOW);
  specs.set_center_to_dribbler(0.07f);
  RobotSpecErForce erforce;
  erforce.set_shoot_radius(0.08f);
  specs.add_custom()->PackFrom(erforce);
  const RobotSpecsTranslation out = translate_robot_specs(all, omni4());
  for (const auto& e : out.errors) ADD_FAILURE() << e.code() << ": " << e.message();
  ASSERT_EQ(out.types.size(), 1u);
  const RobotTypeConfig read =
      parse_robot_type_definition(out.types[0].name, out.types[0].config_text);
  EXPECT_NEAR(read.front_distance, 0.07, 1e-6);
  EXPECT_NEAR(read.kicker_distance, 0.07, 1e-6);
  EXPECT_FALSE(read.has_mouth());
}

// Every team of the official simulation controller's robot-specs.yaml
// (tests/ssl_bridge/data/official_robot_specs.txtpb) translates without a
// single error, into a type physics' reader takes, with each value in place.
TEST(SslRobotSpecs, TheOfficialRobotSpecsOfEveryTeamTranslateWithoutErrors) {
  std::ifstream in(UBERSIM_SSL_TEST_DATA "/official_robot_specs.txtpb");
  ASSERT_TRUE(in) << "fixture missing";
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  SimulatorConfig config;
  ASSERT_TRUE(google::protobuf::TextFormat::ParseFromString(text, &config));
  ASSERT_EQ(config.robot_specs_size(), 16);
  for (RobotSpecs& specs : *config.mutable_robot_specs()) {
    ASSERT_EQ(specs.custom_size(), 1);
    // The simulation controller's type URL (ER-Force's package).
    specs.mutable_custom(0)->set_type_url("type.googleapis.com/sslsim.RobotSpecErForce");
  }
  const RobotSpecsTranslation out = translate_robot_specs(config.robot_specs(), omni4());
  EXPECT_EQ(out.errors.size(), 0u);
  for (const auto& e : out.errors) ADD_FAILURE() << e.code() << ": " << e.message();
  ASSERT_EQ(out.types.size(), 16u);
  int mouths = 0;
  for (int i = 0; i < 16; ++i) {
    const RobotSpecs& spec = config.robot_specs(i);
    RobotSpecErForce erforce;
    ASSERT_TRUE(spec.custom(0).UnpackTo(&erforce) ||
                erforce.ParseFromString(spec.custom(0).value()));
    const DefinedRobotType& type = out.types[static_cast<std::size_t>(i)];
    SCOPED_TRACE(type.name);
    RobotTypeConfig read;
    ASSERT_NO_THROW(read = parse_robot_type_definition(type.name, type.config_text))
        << type.config_text;
    EXPECT_NEAR(read.radius, spec.radius(), 1e-6);
    EXPECT_NEAR(read.height, spec.height(), 1e-6);
    EXPECT_NEAR(read.mass, spec.mass(), 1e-6);
    EXPECT_NEAR(read.kick_max_speed, spec.max_linear_kick_speed(), 1e-6);
    EXPECT_NEAR(read.chip_max_speed, spec.max_chip_kick_speed(), 1e-6);
    EXPECT_NEAR(read.front_distance, spec.center_to_dribbler(), 1e-6);
    EXPECT_NEAR(read.kicker_distance, erforce.shoot_radius(), 1e-6);  // all within the front
    EXPECT_NEAR(read.dribbler_width, erforce.dribbler_width(), 1e-6);
    EXPECT_NEAR(read.kicker_width, erforce.dribbler_width(), 1e-6);
    const RobotLimits& l = spec.limits();
    EXPECT_NEAR(read.max_acceleration, l.acc_speedup_absolute_max(), 1e-5);
    EXPECT_NEAR(read.max_angular_acceleration, l.acc_speedup_angular_max(), 1e-4);
    EXPECT_NEAR(read.max_brake_acceleration, l.acc_brake_absolute_max(), 1e-5);
    EXPECT_NEAR(read.max_angular_brake_acceleration, l.acc_brake_angular_max(), 1e-4);
    EXPECT_NEAR(read.max_speed, l.vel_absolute_max(), 1e-5);
    EXPECT_NEAR(read.max_angular_speed, l.vel_angular_max(), 1e-4);
    if (read.has_mouth()) ++mouths;
  }
  // TIGERs Mannheim (entry 1) brakes harder than it speeds up.
  const RobotTypeConfig tigers =
      parse_robot_type_definition(out.types[1].name, out.types[1].config_text);
  EXPECT_NEAR(tigers.max_acceleration, 4.7, 1e-5);
  EXPECT_NEAR(tigers.max_brake_acceleration, 5.9, 1e-5);
  EXPECT_NEAR(tigers.max_angular_brake_acceleration, 51.6, 1e-4);
  EXPECT_EQ(mouths, 15);  // UBC Thunderbots' ball rests at its flat front
}

TEST(SslRobotSpecs, SpecsDefineATypeThenRebuildTheRobotsWhereTheyStand) {
  const BaseRobotType base = omni4();
  sim_state_t state{};
  robot_state_t robot{};
  robot.team = team_t::BLUE;
  robot.robot_id = 2;
  robot.x = 1.5;
  robot.y = -0.5;
  robot.orientation = 0.25;
  state.robots.push_back(robot);
  robot.team = team_t::YELLOW;
  state.robots.push_back(robot);
  state.num_robots = 2;
  SimControlSettings settings;
  settings.base_robot_type = &base;
  SimulatorCommand command;
  RobotSpecs* specs = command.mutable_config()->add_robot_specs();
  specs->mutable_id()->set_team(BLUE);
  specs->set_radius(0.085f);
  // The same command adds blue 7: it is built from the new type too.
  TeleportRobot* add = command.mutable_control()->add_teleport_robot();
  add->mutable_id()->set_id(7);
  add->mutable_id()->set_team(BLUE);
  add->set_x(0);
  add->set_y(0);
  add->set_present(true);

  const auto out = translate_simulator_command(command, &state, settings);
  EXPECT_TRUE(out.errors.empty());
  ASSERT_EQ(out.requests.size(), 3u);
  EXPECT_EQ(out.requests[0].action, +sim_control_t::DEFINE_ROBOT_TYPE);
  EXPECT_EQ(out.requests[0].robot_type_name, "ssl_specs_blue");
  EXPECT_EQ(out.requests[1].action, +sim_control_t::PLACE);
  ASSERT_EQ(out.requests[1].num_robots, 1);  // only the blue robot
  EXPECT_EQ(out.requests[1].robots[0].robot_type, "ssl_specs_blue");
  EXPECT_DOUBLE_EQ(out.requests[1].robots[0].x, 1.5);
  EXPECT_DOUBLE_EQ(out.requests[1].robots[0].orientation, 0.25);
  EXPECT_EQ(out.requests[2].robots[0].robot_type, "ssl_specs_blue");
  ASSERT_EQ(out.defined_types.size(), 1u);

  // Without a base type, specs are an error and nothing is requested.
  SimControlSettings none;
  command.clear_control();
  const auto refused = translate_simulator_command(command, &state, none);
  EXPECT_TRUE(refused.requests.empty());
  EXPECT_TRUE(mentions(refused.errors, kErrorUnsupported, "config.robot_specs"));
}

TEST(SslRobotSpecs, DefinitionTextIsBoundedAndMayNotNameAFile) {
  EXPECT_THROW(parse_robot_type_definition("x", "BASE = /etc/passwd\n"), ConfigError);
  EXPECT_THROW(parse_robot_type_definition("../x", "MASS = 1\n"), ConfigError);
  EXPECT_THROW(parse_robot_type_definition("x", std::string(20000, '#')), ConfigError);
  EXPECT_THROW(parse_robot_type_definition("x", "MASS = 1\n"), ConfigError);  // keys missing
}
