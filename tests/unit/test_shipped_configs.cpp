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
  EXPECT_EQ(names, (std::vector<std::string>{"division_a", "division_b", "field2002"}));
  const auto b = ubersim::load_field_config(kConfigDir, "division_b");
  EXPECT_DOUBLE_EQ(b.field_length, 9.0);
  EXPECT_DOUBLE_EQ(b.field_width, 6.0);
  const auto a = ubersim::load_field_config(kConfigDir, "division_a");
  EXPECT_DOUBLE_EQ(a.field_length, 12.0);
  EXPECT_DOUBLE_EQ(a.goal_width, 1.8);
  EXPECT_DOUBLE_EQ(a.boundary_width, 0.3);  // from its BASE
  const auto f2002 = ubersim::load_field_config(kConfigDir, "field2002");
  EXPECT_DOUBLE_EQ(f2002.field_length, 2.8);
  EXPECT_DOUBLE_EQ(f2002.field_width, 2.3);
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
