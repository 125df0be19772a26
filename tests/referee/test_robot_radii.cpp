// The referee's radius per robot type, with the type names of SIM_STATE, which
// anyone on the bus may send: a config is read only for a robot type name, the
// names kept are bounded, and nothing throws.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "temp_dir.hpp"
#include "ubersim/referee/robot_radii.hpp"

using ubersim::referee::RobotRadii;

namespace {

// A config folder with robots/small.cfg (radius 0.08 m) and, outside robots/,
// a robot file a path name could reach.
std::string small_robot() {
  return "BASE = " + std::string(UBERSIM_SOURCE_CONFIG_DIR) + "/robots/omni4_ssl.cfg\n" +
         "RADIUS = 0.08\nFRONT_DISTANCE = 0.07\n";
}

}  // namespace

TEST(RobotRadii, ReadsConfigsOnlyForRobotTypeNamesAndKeepsABoundedCache) {
  ubersim::test::TempDir dir;
  dir.write("config/robots/small.cfg", small_robot());
  const std::string outside = dir.write("small.cfg", small_robot());
  RobotRadii radii(dir.path("config"));

  EXPECT_DOUBLE_EQ(radii("small"), 0.08);
  EXPECT_EQ(radii.fallbacks(), 0u);
  // Not names: a path (inside or outside the folder), a file name, nothing,
  // bytes that are not UTF-8, a very long name. None is read, none is kept.
  for (const std::string& hostile :
       {outside, std::string("../small"), std::string("small.cfg"), std::string("robots/small"),
        std::string(), std::string("omni\xff\xfe"), std::string(100000, 's'),
        std::string("/dev/zero")}) {
    EXPECT_DOUBLE_EQ(radii(hostile), RobotRadii::kFallbackRadius) << hostile.substr(0, 40);
  }
  EXPECT_EQ(radii.cached(), 1u);
  EXPECT_EQ(radii.fallbacks(), 8u);

  // A name with no config: the fallback, once looked up, then kept.
  EXPECT_DOUBLE_EQ(radii("no_such_type"), RobotRadii::kFallbackRadius);
  EXPECT_DOUBLE_EQ(radii("no_such_type"), RobotRadii::kFallbackRadius);
  EXPECT_EQ(radii.cached(), 2u);
  EXPECT_EQ(radii.fallbacks(), 9u);

  // A stream of new names: the cache stops growing, known types stay known.
  for (int i = 0; i < 1000; ++i) radii("type_" + std::to_string(i));
  EXPECT_EQ(radii.cached(), RobotRadii::kMaxTypes);
  EXPECT_DOUBLE_EQ(radii("small"), 0.08);
  EXPECT_DOUBLE_EQ(radii("type_999"), RobotRadii::kFallbackRadius);
}
