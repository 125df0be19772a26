// Every config file we ship loads with the schema of its kind, and every
// scenario puts its robots inside the field without overlaps.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "ubersim/config.hpp"
#include "ubersim/field_config.hpp"
#include "ubersim/robot_config.hpp"
#include "ubersim/scenario_config.hpp"

namespace fs = std::filesystem;
const std::string kConfigDir = UBERSIM_SOURCE_CONFIG_DIR;

std::vector<std::string> names_of(const std::string& kind) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(fs::path(kConfigDir) / kind)) {
    if (entry.path().extension() == ".cfg") names.push_back(entry.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

TEST(ShippedConfigs, EveryFileParses) {
  int count = 0;
  for (const auto& entry : fs::recursive_directory_iterator(kConfigDir)) {
    if (entry.path().extension() != ".cfg") continue;
    EXPECT_NO_THROW(ubersim::ConfigFile::load(entry.path())) << entry.path();
    ++count;
  }
  EXPECT_GE(count, 10);
}

TEST(ShippedConfigs, FieldsLoad) {
  const auto names = names_of("fields");
  EXPECT_EQ(names, (std::vector<std::string>{
                       "division_a", "division_b", "erforce_2014", "erforce_2017", "erforce_2018",
                       "erforce_2019", "erforce_2020", "erforce_2020b", "erforce_2023",
                       "erforce_2023b", "field2002", "rsim_hardware_challenge"}));
  for (const auto& name : names) {
    EXPECT_NO_THROW(ubersim::load_field_config(kConfigDir, name)) << name;
  }
  // 2026 official fields (ssl-vision's defaults, the game controller's penalty distances).
  const auto b = ubersim::load_field_config(kConfigDir, "division_b");
  EXPECT_DOUBLE_EQ(b.field_length, 9.0);
  EXPECT_DOUBLE_EQ(b.field_width, 6.0);
  EXPECT_DOUBLE_EQ(b.penalty_mark_distance, 6.0);
  EXPECT_DOUBLE_EQ(b.boundary_width, 0.3);
  EXPECT_DOUBLE_EQ(b.boundary_width_goal_line, 0.6);
  EXPECT_DOUBLE_EQ(b.goal_substitution_area_width, 0.3);
  const auto a = ubersim::load_field_config(kConfigDir, "division_a");
  EXPECT_DOUBLE_EQ(a.field_length, 12.0);
  EXPECT_DOUBLE_EQ(a.goal_width, 1.8);
  EXPECT_DOUBLE_EQ(a.boundary_width, 0.3);
  EXPECT_DOUBLE_EQ(a.boundary_width_goal_line, 0.6);
  EXPECT_DOUBLE_EQ(a.goal_substitution_area_width, 0.3);
  EXPECT_DOUBLE_EQ(a.penalty_mark_distance, 8.0);
  EXPECT_DOUBLE_EQ(a.wall_thickness, 0.05);  // from its BASE
  const auto f2002 = ubersim::load_field_config(kConfigDir, "field2002");
  EXPECT_DOUBLE_EQ(f2002.field_length, 2.8);
  EXPECT_DOUBLE_EQ(f2002.field_width, 2.3);
  EXPECT_DOUBLE_EQ(f2002.penalty_mark_distance, 0.45);
  // Without the optional keys: one margin all round, the SSL substitution area or less.
  EXPECT_DOUBLE_EQ(f2002.boundary_width_goal_line, f2002.boundary_width);
  EXPECT_DOUBLE_EQ(f2002.goal_substitution_area_width, 0.2);
  // ER-Force's presets: its numbers (config/simulator/*.txt at 9814d057).
  const auto e2020 = ubersim::load_field_config(kConfigDir, "erforce_2020");
  EXPECT_DOUBLE_EQ(e2020.field_length, 12.04);
  EXPECT_DOUBLE_EQ(e2020.field_width, 9.02);
  EXPECT_DOUBLE_EQ(e2020.boundary_width, 0.25);
  EXPECT_DOUBLE_EQ(e2020.boundary_width_goal_line, 0.25);
  EXPECT_DOUBLE_EQ(e2020.penalty_mark_distance, 1.8);
  const auto e2014 = ubersim::load_field_config(kConfigDir, "erforce_2014");
  EXPECT_DOUBLE_EQ(e2014.field_length, 6.03);
  EXPECT_DOUBLE_EQ(e2014.goal_width, 0.69);
  EXPECT_DOUBLE_EQ(e2014.penalty_area_width, 0.32 + 2 * 0.81);
  const auto e2023b = ubersim::load_field_config(kConfigDir, "erforce_2023b");
  EXPECT_DOUBLE_EQ(e2023b.field_length, 9.0);
  EXPECT_DOUBLE_EQ(e2023b.boundary_width, 0.3);
}

TEST(ShippedConfigs, FieldKeysAreCheckedAgainstTheField) {
  const auto field = [](const std::string& text) {
    return ubersim::load_field_config(ubersim::ConfigFile::parse(text, "f.cfg"), "f");
  };
  const std::string base =
      "FIELD_LENGTH = 9\nFIELD_WIDTH = 6\nBOUNDARY_WIDTH = 0.3\nLINE_WIDTH = 0.01\n"
      "GOAL_WIDTH = 1\nGOAL_DEPTH = 0.18\nGOAL_HEIGHT = 0.155\nGOAL_WALL_THICKNESS = 0.02\n"
      "WALL_HEIGHT = 0.1\nWALL_THICKNESS = 0.05\nCENTER_CIRCLE_RADIUS = 0.5\n"
      "PENALTY_AREA_DEPTH = 1\nPENALTY_AREA_WIDTH = 2\nWALL_RESTITUTION = 0.6\n"
      "WALL_FRICTION = 0.3\n";
  // The penalty mark may lie anywhere from the goal attacked to the other goal line.
  EXPECT_DOUBLE_EQ(field(base + "PENALTY_MARK_DISTANCE = 9\n").penalty_mark_distance, 9.0);
  EXPECT_THROW(field(base + "PENALTY_MARK_DISTANCE = 9.01\n"), ubersim::ConfigError);
  // The substitution area lies within the area behind the goal line.
  const auto wide = field(base +
                          "PENALTY_MARK_DISTANCE = 6\nBOUNDARY_WIDTH_GOAL_LINE = 0.6\n"
                          "GOAL_SUBSTITUTION_AREA_WIDTH = 0.6\n");
  EXPECT_DOUBLE_EQ(wide.half_length_to_wall(), 4.5 + 0.6);
  EXPECT_DOUBLE_EQ(wide.half_width_to_wall(), 3.0 + 0.3);
  EXPECT_THROW(field(base + "PENALTY_MARK_DISTANCE = 6\nGOAL_SUBSTITUTION_AREA_WIDTH = 0.31\n"),
               ubersim::ConfigError);
  // A goal deeper than the room behind the goal line (plus wall) would stick out of the wall.
  EXPECT_THROW(field(base + "PENALTY_MARK_DISTANCE = 6\nBOUNDARY_WIDTH_GOAL_LINE = 0.1\n"),
               ubersim::ConfigError);
}

TEST(ShippedConfigs, RobotsLoad) {
  for (const auto& name : names_of("robots")) {
    const auto robot = ubersim::load_robot_config(kConfigDir, name);
    EXPECT_LE(robot.radius, 0.09 + 1e-9) << name << ": SSL robots fit in 0.18 m";
    EXPECT_LE(robot.height, 0.15 + 1e-9) << name;
    EXPECT_GE(robot.wheels.size(), 2u) << name;
  }
  const auto diff = ubersim::load_robot_config(kConfigDir, "diff_drive_cmdragons02");
  EXPECT_EQ(diff.drive, ubersim::DriveKind::Differential);
  const auto omni3 = ubersim::load_robot_config(kConfigDir, "omni3_cmdragons02");
  EXPECT_EQ(omni3.wheels.size(), 3u);
  const auto planar = ubersim::load_robot_config(kConfigDir, "omni4_ssl_planar");
  EXPECT_EQ(planar.model, ubersim::DriveModel::Planar);
  EXPECT_EQ(planar.wheels.size(), 4u);
}

TEST(ShippedConfigs, ScenariosPlaceRobotsLegally) {
  for (const auto& name : names_of("scenarios")) {
    SCOPED_TRACE(name);
    const auto scenario = ubersim::load_scenario_config(kConfigDir, name);
    const auto field = ubersim::load_field_config(kConfigDir, scenario.field);
    ASSERT_FALSE(scenario.robots.empty());
    for (std::size_t i = 0; i < scenario.robots.size(); ++i) {
      const auto& r = scenario.robots[i];
      const auto type = ubersim::load_robot_config(kConfigDir, r.type);
      EXPECT_LE(std::abs(r.x) + type.radius, field.field_length / 2) << r.id;
      EXPECT_LE(std::abs(r.y) + type.radius, field.field_width / 2) << r.id;
      EXPECT_GT(std::hypot(r.x - scenario.ball_x, r.y - scenario.ball_y), type.radius + 0.03);
      for (std::size_t j = i + 1; j < scenario.robots.size(); ++j) {
        const auto& o = scenario.robots[j];
        EXPECT_GT(std::hypot(r.x - o.x, r.y - o.y), 2 * type.radius + 0.01)
            << ubersim::team_name(r.team) << r.id << " vs " << ubersim::team_name(o.team) << o.id;
      }
    }
  }
}

TEST(ShippedConfigs, ScenarioErrorsNameKeyAndLine) {
  const auto config = ubersim::ConfigFile::parse(
      "FIELD = division_b\nBALL = b\nBALL_POSITION = 0 0\nYELLOW_0 = omni4_ssl 1.0 abc 0\n",
      "s.cfg");
  try {
    ubersim::load_scenario_config(config, "s");
    FAIL();
  } catch (const ubersim::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("s.cfg:4: YELLOW_0: expected a real number for y"),
              std::string::npos)
        << e.what();
  }
  const auto unknown = ubersim::ConfigFile::parse(
      "FIELD = division_b\nBALL = b\nBALL_POSITION = 0 0\nGREEN_0 = omni4_ssl 1 1 0\n", "s.cfg");
  EXPECT_THROW(ubersim::load_scenario_config(unknown, "s"), ubersim::ConfigError);
}
