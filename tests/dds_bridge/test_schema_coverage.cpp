// The generated schema code (dds_bridge/gen_dds_bridge.py) covers every field
// of every bridged .lcm type:
//  * the generator read every member: the LCM fingerprint computed from what
//    its parser (lcmtypes/lcm_schema.py) read equals lcm-gen's (Msg::getHash()
//    hashes every member's name, type and dimensions; test_lcm_fields checks
//    every type, this the bridged ones);
//  * to_dds/from_dds carry every field: messages with every leaf field set at
//    random (strings, integers, booleans, reals incl. NaN payloads) come back
//    with identical LCM encodings;
//  * the finite check sees every real field: NaN or Inf put into any one of
//    them is reported by that field's path, and the sample is dropped.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

#include "sample_messages.hpp"
#include "ubersim/dds_bridge/convert.hpp"
#include "ubersim/dds_bridge/echo_filter.hpp"
#include "ubersim/dds_bridge/sample_checks.hpp"
#include "ubersim/lcm_fields.hpp"

namespace dds = ubersim::dds;
using Kind = ubersim::FieldKind;
using ubersim::LcmFields;

namespace {

// Topic types with a message of every array non-empty (so that the fields of
// the types inside them are reached too).
auto topic_messages() {
  return std::make_tuple(
      dds_test::vision_frame(17), dds_test::field_geometry(0.5), dds_test::vision_geometry(1.5),
      dds_test::radio_packet(1, 99), dds_test::radio_feedback(0, 2.0), dds_test::sim_commands(1, 5),
      dds_test::sim_state(1234, 2), dds_test::sim_control(77), dds_test::sim_control_ack(78));
}

template <class Visit>
void for_each_topic_message(Visit&& visit) {
  auto messages = topic_messages();
  std::apply([&](auto&... message) { (visit(message), ...); }, messages);
}

// Sets every leaf field at random; reals are sometimes NaN (with a payload) or Inf.
class RandomFill {
 public:
  explicit RandomFill(unsigned seed) : rng_(seed) {}

  template <class Field>
  void operator()(const std::string& /*path*/, Field& field, Kind kind) {
    if constexpr (std::is_same_v<Field, std::string>) {
      field.assign(rng_() % 12, 'a');
      for (char& c : field) c = static_cast<char>('a' + rng_() % 26);
    } else if constexpr (std::is_floating_point_v<Field>) {
      field = real<Field>();
    } else if (kind == Kind::kBoolean) {
      field = static_cast<Field>(rng_() % 2);
    } else {
      field = static_cast<Field>(rng_());
    }
    ++fields_set;
  }

  int fields_set = 0;

 private:
  template <class Real>
  Real real() {
    switch (rng_() % 16) {
      case 0:
        return std::numeric_limits<Real>::quiet_NaN();
      case 1:
        return -std::numeric_limits<Real>::infinity();
      case 2:
        return static_cast<Real>(std::nan("7"));
      default:
        return static_cast<Real>(std::uniform_real_distribution<double>(-1e6, 1e6)(rng_));
    }
  }
  std::mt19937 rng_;
};

// The paths of every real field of a message.
template <class Msg>
std::vector<std::string> real_fields(Msg message) {
  std::vector<std::string> paths;
  auto collect = [&](const std::string& path, auto& /*field*/, Kind kind) {
    if (kind == Kind::kReal) paths.push_back(path);
  };
  LcmFields<Msg>::visit(message, "", collect);
  return paths;
}

// Sets the real field at `target` to `value`.
template <class Msg>
void set_real(Msg& message, const std::string& target, double value) {
  auto set = [&](const std::string& path, auto& field, Kind kind) {
    if constexpr (std::is_floating_point_v<std::remove_reference_t<decltype(field)>>) {
      if (kind == Kind::kReal && path == target)
        field = static_cast<std::decay_t<decltype(field)>>(value);
    }
  };
  LcmFields<Msg>::visit(message, "", set);
}

template <class Msg>
void expect_parsed_hash() {
  EXPECT_EQ(LcmFields<Msg>::kParsedHash, static_cast<std::uint64_t>(Msg::getHash()))
      << Msg::getTypeName() << ": the generator did not read what lcm-gen read";
}

template <class... Msgs>
void expect_parsed_hashes(std::tuple<Msgs...> /*types*/) {
  (expect_parsed_hash<Msgs>(), ...);
}

}  // namespace

TEST(DdsSchema, GeneratorReadEveryMemberOfEveryBridgedType) {
  using namespace ubersim;
  expect_parsed_hashes(
      std::tuple<vision_ball_t, vision_robot_t, vision_frame_t, field_geometry_t,
                 camera_calibration_t, vision_geometry_t, robot_command_t, radio_packet_t,
                 robot_feedback_t, radio_feedback_t, sim_commands_t, body_state_t, robot_state_t,
                 sim_state_t, robot_placement_t, ball_placement_t, sim_control_t,
                 sim_control_ack_t>{});
}

TEST(DdsSchema, RandomlyFilledMessagesRoundTripUnchanged) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    for_each_topic_message([&](auto message) {
      using Msg = decltype(message);
      RandomFill fill(seed);
      LcmFields<Msg>::visit(message, "", fill);
      ASSERT_GT(fill.fields_set, 0) << Msg::getTypeName();
      const Msg back = dds::from_dds(dds::to_dds(message).get());
      EXPECT_EQ(dds::lcm_bytes(back), dds::lcm_bytes(message))
          << Msg::getTypeName() << ", seed " << seed;
    });
  }
}

TEST(DdsSchema, NonFiniteValueInAnyRealFieldIsFoundByItsPath) {
  int checked = 0;
  for_each_topic_message([&](const auto& good) {
    using Msg = std::decay_t<decltype(good)>;
    ASSERT_EQ(dds::non_finite_field(good), "") << Msg::getTypeName();
    for (const std::string& path : real_fields(good)) {
      for (double bad :
           {std::numeric_limits<double>::quiet_NaN(), -std::numeric_limits<double>::infinity()}) {
        Msg message = good;
        set_real(message, path, bad);
        EXPECT_EQ(dds::non_finite_field(message), path) << Msg::getTypeName();
        ++checked;
      }
    }
  });
  EXPECT_GT(checked, 400);  // vision frames, states of 4 robots, cameras, ...
}

TEST(DdsSchema, NonFiniteSamplesAreDropped) {
  // Every type the bridge admits by the finite check alone: NaN anywhere drops it.
  auto expect_dropped = [](const auto& good) {
    for (const std::string& path : real_fields(good)) {
      auto message = good;
      set_real(message, path, std::numeric_limits<double>::quiet_NaN());
      const dds::Admission admission = dds::admit(message);
      EXPECT_FALSE(admission.forward) << path;
      ASSERT_EQ(admission.findings.size(), 1u) << path;
      EXPECT_EQ(admission.findings[0].detail, path + " is not finite");
    }
  };
  expect_dropped(dds_test::vision_frame(3));
  expect_dropped(dds_test::field_geometry());
  expect_dropped(dds_test::vision_geometry());
  expect_dropped(dds_test::radio_feedback(1));
  expect_dropped(dds_test::sim_state(5, 2));
  expect_dropped(dds_test::sim_control(4));
  expect_dropped(dds_test::sim_control_ack(4));
  // SIM_COMMANDS: outside the commands (which the radio validator judges entry
  // by entry), a non-finite number drops the message.
  const ubersim::radio::CommandLimits limits{10, 60, 1000, 20, 5000};
  for (const std::string& path : real_fields(dds_test::sim_commands(0, 1))) {
    if (path.rfind("commands[", 0) == 0) continue;
    auto commands = dds_test::sim_commands(0, 1);
    set_real(commands, path, std::numeric_limits<double>::infinity());
    const dds::Admission admission = dds::admit_commands(commands, limits);
    EXPECT_FALSE(admission.forward) << path;
    EXPECT_EQ(commands.commands.size(), 3u) << "the message is left whole: " << path;
  }
}
