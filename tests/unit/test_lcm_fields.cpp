// The parser every generator shares (lcmtypes/lcm_schema.py) reads every
// member of every .lcm type as lcm-gen does: the fingerprint gen_lcm_fields.py
// computes from what it read equals lcm-gen's getHash() (which hashes each
// member's name, type and dimensions). And the visitor reaches every field.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <ubersim/encoded_bounds.hpp>
#include <ubersim/lcm_fields.hpp>
#include <vector>

namespace {

template <class Msg>
void expect_parsed_hash() {
  EXPECT_EQ(ubersim::LcmFields<Msg>::kParsedHash, static_cast<std::uint64_t>(Msg::getHash()))
      << Msg::getTypeName() << ": the .lcm parser did not read what lcm-gen read";
}

template <class... Msgs>
int expect_parsed_hashes(ubersim::LcmTypeList<Msgs...> /*types*/) {
  (expect_parsed_hash<Msgs>(), ...);
  return static_cast<int>(sizeof...(Msgs));
}

}  // namespace

TEST(LcmFields, ParserReadsEveryMemberOfEveryType) {
  EXPECT_GE(expect_parsed_hashes(ubersim::AllLcmTypes{}), 28);
}

TEST(LcmFields, VisitNamesEveryLeafByItsPath) {
  ubersim::sim_state_t state{};
  state.robots.resize(2);
  state.robots[1].wheel_speeds = {1, 2, 3};
  state.robots[1].num_wheels = 3;
  state.num_robots = 2;
  std::vector<std::string> reals;
  int texts = 0;
  auto collect = [&](const std::string& path, const auto& /*field*/, ubersim::FieldKind kind) {
    if (kind == ubersim::FieldKind::kReal) reals.push_back(path);
    if (kind == ubersim::FieldKind::kText) ++texts;
  };
  const ubersim::sim_state_t& view = state;
  ubersim::LcmFields<ubersim::sim_state_t>::visit(view, "", collect);
  // 3 of the state, 13 of the ball, 6 + 13 + 1 per robot, and 3 wheel speeds.
  EXPECT_EQ(reals.size(), 3u + 13u + 2 * 20u + 3u);
  EXPECT_EQ(texts, 2);  // robot_type of each robot
  EXPECT_EQ(reals.front(), "sim_time");
  EXPECT_EQ(reals.back(), "robots[1].last_command_time");
  EXPECT_NE(std::find(reals.begin(), reals.end(), "robots[1].wheel_speeds[2]"), reals.end());
  EXPECT_NE(std::find(reals.begin(), reals.end(), "ball.angular_velocity[2]"), reals.end());
}
