// The geometries the official ssl-simulation-controller applies (Division A
// and B, tests/ssl_bridge/data/simctl_geometry_div_*.txt, its files verbatim)
// through the real translation and the real field-change reader that physics
// runs: no error about the field, and the field ubersim then plays on is the
// one the official programs mean.
#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "ubersim/field_change.hpp"
#include "ubersim/field_config.hpp"
#include "ubersim/ssl_bridge/geometry_change_translation.hpp"
#include "ubersim/ssl_bridge/vision_translation.hpp"

using namespace ubersim;
using namespace ubersim::ssl;

namespace {

constexpr double kBallRadius = 0.0215;  // m, config/balls/ssl_standard.cfg

SSL_GeometryData official_geometry(const std::string& division) {
  const std::string path =
      std::string(UBERSIM_SSL_TEST_DATA) + "/simctl_geometry_div_" + division + ".txt";
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  SSL_GeometryData geometry;
  if (!in || !google::protobuf::TextFormat::ParseFromString(text.str(), &geometry)) {
    ADD_FAILURE() << "cannot parse " << path;
  }
  return geometry;
}

FieldConfig field_in_use() {
  return load_field_config(UBERSIM_SOURCE_CONFIG_DIR, "division_b");
}

// The errors that are not about the cameras (geometry.calib is another part's).
Errors field_errors(const Errors& errors) {
  Errors out;
  for (const auto& e : errors) {
    if (e.message().rfind("geometry.calib", 0) != 0) out.push_back(e);
  }
  return out;
}

// What physics does with the SET_FIELD text (World::change_field's reader).
FieldConfig applied(const SSL_GeometryData& geometry, const FieldConfig& current) {
  const field_geometry_t reported = current.to_message(kBallRadius);
  const GeometryChange change = translate_geometry(geometry, &reported);
  EXPECT_TRUE(field_errors(change.errors).empty()) << field_errors(change.errors).front().message();
  EXPECT_TRUE(change.field_config.has_value());
  return change_field(current, change.field_config.value_or(""));
}

}  // namespace

TEST(SslOfficialGeometry, DivisionAAppliesWithoutAnErrorAboutTheField) {
  SSL_GeometryData geometry = official_geometry("a");
  ASSERT_EQ(geometry.field().goal_center_to_penalty_mark(), 8000);
  const FieldConfig f = applied(geometry, field_in_use());
  EXPECT_DOUBLE_EQ(f.field_length, 12.0);
  EXPECT_DOUBLE_EQ(f.field_width, 9.0);
  EXPECT_DOUBLE_EQ(f.goal_width, 1.8);
  EXPECT_DOUBLE_EQ(f.goal_depth, 0.3);
  EXPECT_DOUBLE_EQ(f.goal_height, 0.155);
  EXPECT_DOUBLE_EQ(f.boundary_width, 0.3);
  // The file has no field 16: the protocol's (and the GC's) reading is "as along the touch lines".
  EXPECT_DOUBLE_EQ(f.boundary_width_goal_line, 0.3);
  EXPECT_DOUBLE_EQ(f.penalty_area_depth, 1.8);
  EXPECT_DOUBLE_EQ(f.penalty_area_width, 3.6);
  EXPECT_DOUBLE_EQ(f.center_circle_radius, 0.5);
  EXPECT_DOUBLE_EQ(f.line_width, 0.01);
  EXPECT_DOUBLE_EQ(f.penalty_mark_distance, 8.0);
  EXPECT_DOUBLE_EQ(f.goal_substitution_area_width, 0.3);  // kept from the field in use
  EXPECT_DOUBLE_EQ(f.half_length_to_wall(), 6.3);

  // With the cameras left out nothing at all is refused.
  geometry.clear_calib();
  const field_geometry_t reported = field_in_use().to_message(kBallRadius);
  EXPECT_TRUE(translate_geometry(geometry, &reported).errors.empty());
}

TEST(SslOfficialGeometry, DivisionBAppliesWithoutAnErrorAboutTheField) {
  SSL_GeometryData geometry = official_geometry("b");
  const FieldConfig f =
      applied(geometry, load_field_config(UBERSIM_SOURCE_CONFIG_DIR, "division_a"));
  EXPECT_DOUBLE_EQ(f.field_length, 9.0);
  EXPECT_DOUBLE_EQ(f.field_width, 6.0);
  EXPECT_DOUBLE_EQ(f.goal_width, 1.0);
  EXPECT_DOUBLE_EQ(f.penalty_area_depth, 1.0);
  EXPECT_DOUBLE_EQ(f.penalty_area_width, 2.0);
  EXPECT_DOUBLE_EQ(f.penalty_mark_distance, 6.0);
  EXPECT_DOUBLE_EQ(f.boundary_width, 0.3);
  EXPECT_DOUBLE_EQ(f.boundary_width_goal_line, 0.3);  // division_a had 0.6: field 16 absent

  geometry.clear_calib();
  const field_geometry_t reported = field_in_use().to_message(kBallRadius);
  EXPECT_TRUE(translate_geometry(geometry, &reported).errors.empty());
}

TEST(SslOfficialGeometry, GoalLineBoundaryAndSubstitutionAreaAreApplied) {
  SSL_GeometryData geometry = official_geometry("a");
  geometry.clear_calib();
  geometry.mutable_field()->set_boundary_width_goal_line(600);
  geometry.mutable_field()->set_goal_substitution_area_width(250);
  geometry.mutable_field()->set_goal_height(160);
  const FieldConfig f = applied(geometry, field_in_use());
  EXPECT_DOUBLE_EQ(f.boundary_width, 0.3);
  EXPECT_DOUBLE_EQ(f.boundary_width_goal_line, 0.6);
  EXPECT_DOUBLE_EQ(f.goal_substitution_area_width, 0.25);
  EXPECT_DOUBLE_EQ(f.goal_height, 0.16);
  EXPECT_DOUBLE_EQ(f.half_length_to_wall(), 6.6);
  EXPECT_DOUBLE_EQ(f.half_width_to_wall(), 4.8);
}

TEST(SslOfficialGeometry, SubstitutionAreaNotSentShrinksWithTheAreaBehindTheGoalLine) {
  SSL_GeometryData geometry = official_geometry("b");
  geometry.clear_calib();
  geometry.mutable_field()->set_boundary_width(200);  // less than the 0.3 m in use
  geometry.mutable_field()->set_goal_depth(180);      // 300 mm would not fit behind the line
  const FieldConfig f = applied(geometry, field_in_use());
  EXPECT_DOUBLE_EQ(f.boundary_width_goal_line, 0.2);
  EXPECT_DOUBLE_EQ(f.goal_substitution_area_width, 0.2);
}

TEST(SslOfficialGeometry, BallRadiusWithinHalfAMillimetreIsOursAndOtherwiseApplied) {
  SSL_GeometryData geometry = official_geometry("a");
  geometry.clear_calib();
  const field_geometry_t reported = field_in_use().to_message(kBallRadius);
  geometry.mutable_field()->set_ball_radius(21.9f);
  GeometryChange change = translate_geometry(geometry, &reported);
  EXPECT_TRUE(change.errors.empty());
  EXPECT_EQ(change.field_config->find("BALL_RADIUS"), std::string::npos);  // ours stays

  geometry.mutable_field()->set_ball_radius(25.0f);
  change = translate_geometry(geometry, &reported);
  EXPECT_TRUE(change.errors.empty());
  EXPECT_NE(change.field_config->find("BALL_RADIUS = 0.025\n"), std::string::npos);
  const FieldChange applied = change_field_and_ball(field_in_use(), *change.field_config);
  ASSERT_TRUE(applied.ball_radius.has_value());
  EXPECT_DOUBLE_EQ(*applied.ball_radius, 0.025);
  // A plain field config has no ball: change_field refuses the key.
  EXPECT_THROW(change_field(field_in_use(), "BALL_RADIUS = 0.025\n"), ConfigError);

  for (float bad : {std::nanf(""), -21.5f, 500.0f}) {
    geometry.mutable_field()->set_ball_radius(bad);
    change = translate_geometry(geometry, &reported);
    ASSERT_EQ(change.errors.size(), 1u) << bad;
    EXPECT_EQ(change.errors[0].code(), kErrorInvalid);
    EXPECT_EQ(change.field_config->find("BALL_RADIUS"), std::string::npos);
  }
}

// What ubersim announces for a shipped field config reads back as the same field.
TEST(SslOfficialGeometry, OurVisionGeometryTranslatesBackToTheSameField) {
  for (const char* name : {"division_a", "division_b", "erforce_2014", "field2002"}) {
    SCOPED_TRACE(name);
    const FieldConfig original = load_field_config(UBERSIM_SOURCE_CONFIG_DIR, name);
    vision_geometry_t announced{};
    announced.field = original.to_message(kBallRadius);
    const SSL_WrapperPacket packet = geometry_packet(announced, {});
    const FieldConfig back = applied(packet.geometry(), field_in_use());
    EXPECT_NEAR(back.field_length, original.field_length, 5e-4);
    EXPECT_NEAR(back.field_width, original.field_width, 5e-4);
    EXPECT_NEAR(back.boundary_width, original.boundary_width, 5e-4);
    EXPECT_NEAR(back.boundary_width_goal_line, original.boundary_width_goal_line, 5e-4);
    EXPECT_NEAR(back.goal_substitution_area_width, original.goal_substitution_area_width, 5e-4);
    EXPECT_NEAR(back.penalty_mark_distance, original.penalty_mark_distance, 5e-4);
    EXPECT_NEAR(back.goal_height, original.goal_height, 5e-4);
  }
}
