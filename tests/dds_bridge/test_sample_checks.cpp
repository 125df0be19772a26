// What the bridge lets through from DDS: radio samples pass the radio
// emulator's own validator; every other type is dropped on NaN/Inf.
#include <gtest/gtest.h>

#include <limits>

#include "sample_messages.hpp"
#include "ubersim/dds_bridge/sample_checks.hpp"

namespace dds = ubersim::dds;
using ubersim::Team;

namespace {

const ubersim::radio::CommandLimits kLimits{10, 60, 1000, 20, 5000};
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

bool has(const dds::Admission& admission, const std::string& problem) {
  for (const auto& finding : admission.findings)
    if (finding.problem == problem) return true;
  return false;
}

std::vector<std::int32_t> ids(const ubersim::radio_packet_t& p) {
  std::vector<std::int32_t> out;
  for (const auto& c : p.commands) out.push_back(c.robot_id);
  return out;
}

}  // namespace

TEST(SampleChecks, GoodRadioPacketGoesOnUnchanged) {
  ubersim::radio_packet_t packet = dds_test::radio_packet(0, 4);
  const auto before = packet;
  const auto admission = dds::admit_radio(packet, Team::Yellow, kLimits);
  EXPECT_TRUE(admission.forward);
  EXPECT_TRUE(admission.findings.empty());
  EXPECT_EQ(admission.entries_removed, 0u);
  EXPECT_EQ(ids(packet), ids(before));
  EXPECT_EQ(packet.commands[2].wheel_speeds, before.commands[2].wheel_speeds);
  EXPECT_EQ(packet.sequence, 4);
}

TEST(SampleChecks, NaNEntryIsRemovedTheRestGoesOn) {
  ubersim::radio_packet_t packet = dds_test::radio_packet(0, 4);
  packet.commands[1].vx = kNaN;
  const auto admission = dds::admit_radio(packet, Team::Yellow, kLimits);
  EXPECT_TRUE(admission.forward);
  EXPECT_EQ(admission.entries_removed, 1u);
  EXPECT_TRUE(has(admission, "NaN/Inf"));
  EXPECT_EQ(ids(packet), (std::vector<std::int32_t>{0, 5}));
  EXPECT_EQ(packet.num_commands, 2);
}

TEST(SampleChecks, AbsurdSpeedIsRemoved) {
  ubersim::radio_packet_t packet = dds_test::radio_packet(1, 4);
  packet.commands[0].vx = 150;  // m/s: a unit error (mm/s?), beyond LIMIT_SPEED
  const auto admission = dds::admit_radio(packet, Team::Blue, kLimits);
  EXPECT_TRUE(admission.forward);
  EXPECT_TRUE(has(admission, "absurd value"));
  EXPECT_EQ(ids(packet), (std::vector<std::int32_t>{3, 5}));
}

TEST(SampleChecks, PacketWithOnlyBadEntriesIsDropped) {
  ubersim::radio_packet_t packet = dds_test::radio_packet(0, 4);
  packet.commands[0].omega = kInf;
  packet.commands[1].kick_speed = -1;
  packet.commands[2].mode = 9;
  const auto admission = dds::admit_radio(packet, Team::Yellow, kLimits);
  EXPECT_FALSE(admission.forward);
  EXPECT_EQ(admission.entries_removed, 0u);  // counted as one dropped packet instead
  EXPECT_TRUE(has(admission, "NaN/Inf"));
  EXPECT_TRUE(has(admission, "absurd value"));
  EXPECT_TRUE(has(admission, "unknown mode"));
}

TEST(SampleChecks, EmptyPacketGoesOnAsItCame) {
  ubersim::radio_packet_t packet = dds_test::radio_packet(0, 4);
  packet.commands.clear();
  packet.num_commands = 0;
  const auto admission = dds::admit_radio(packet, Team::Yellow, kLimits);
  EXPECT_TRUE(admission.forward);
  EXPECT_TRUE(admission.findings.empty());
}

TEST(SampleChecks, WrongOrUnknownTeamDropsThePacket) {
  ubersim::radio_packet_t blue_on_yellow = dds_test::radio_packet(1, 4);
  const auto mismatch = dds::admit_radio(blue_on_yellow, Team::Yellow, kLimits);
  EXPECT_FALSE(mismatch.forward);
  EXPECT_TRUE(has(mismatch, "team does not match channel"));

  ubersim::radio_packet_t unknown = dds_test::radio_packet(7, 4);
  const auto bad_team = dds::admit_radio(unknown, Team::Yellow, kLimits);
  EXPECT_FALSE(bad_team.forward);
  EXPECT_TRUE(has(bad_team, "unknown team"));
}

TEST(SampleChecks, RobotIdsAreNotJudgedWithoutAField) {
  // The bridge does not know who is on the field: any id passes here (the
  // radio emulator downstream judges that), but duplicates do not.
  ubersim::radio_packet_t packet = dds_test::radio_packet(0, 4);
  packet.commands[0].robot_id = 77;
  packet.commands[1].robot_id = 5;  // same as the wheel-speed entry
  const auto admission = dds::admit_radio(packet, Team::Yellow, kLimits);
  EXPECT_TRUE(admission.forward);
  EXPECT_TRUE(has(admission, "duplicate robot id"));
  EXPECT_EQ(ids(packet), (std::vector<std::int32_t>{77}));
}

TEST(SampleChecks, WheelSpeedModeWithoutWheelsIsRemoved) {
  ubersim::radio_packet_t packet = dds_test::radio_packet(0, 4);
  packet.commands[2].wheel_speeds.clear();
  packet.commands[2].num_wheels = 0;
  const auto admission = dds::admit_radio(packet, Team::Yellow, kLimits);
  EXPECT_TRUE(has(admission, "wrong wheel count"));
  EXPECT_EQ(ids(packet), (std::vector<std::int32_t>{0, 3}));
}

TEST(SampleChecks, SimCommandsPassTheSameValidator) {
  ubersim::sim_commands_t commands = dds_test::sim_commands(1, 8);
  commands.commands[2].wheel_speeds[1] = 1e6;  // rad/s, beyond LIMIT_WHEEL_SPEED
  const auto admission = dds::admit_commands(commands, kLimits);
  EXPECT_TRUE(admission.forward);
  EXPECT_TRUE(has(admission, "absurd value"));
  EXPECT_EQ(commands.num_commands, 2);
  EXPECT_EQ(commands.team, 1);
  EXPECT_EQ(commands.sequence, 8);

  ubersim::sim_commands_t late = dds_test::sim_commands(0, 9);
  late.t_apply = kNaN;
  EXPECT_FALSE(dds::admit_commands(late, kLimits).forward);
}

TEST(SampleChecks, NonFiniteValueDropsOtherTypesWhole) {
  ubersim::vision_frame_t frame = dds_test::vision_frame(1);
  EXPECT_TRUE(dds::admit(frame).forward);
  frame.robots_blue[2].y = kNaN;
  const auto admission = dds::admit(frame);
  EXPECT_FALSE(admission.forward);
  ASSERT_EQ(admission.findings.size(), 1u);
  EXPECT_EQ(admission.findings[0].problem, "NaN/Inf");
  EXPECT_NE(admission.findings[0].detail.find("robots_blue[2].y"), std::string::npos);

  ubersim::sim_control_t control = dds_test::sim_control(1);
  EXPECT_TRUE(dds::admit(control).forward);
  control.ball.linear_velocity[2] = -kInf;
  EXPECT_EQ(dds::non_finite_field(control), "ball.linear_velocity[2]");

  ubersim::sim_state_t state = dds_test::sim_state(1);
  EXPECT_TRUE(dds::admit(state).forward);
  state.robots[13].wheel_speeds[3] = kNaN;
  EXPECT_EQ(dds::non_finite_field(state), "robots[13].wheel_speeds[3]");

  ubersim::vision_geometry_t geometry = dds_test::vision_geometry();
  EXPECT_TRUE(dds::admit(geometry).forward);
  geometry.cameras[1].orientation[0] = kNaN;
  EXPECT_EQ(dds::non_finite_field(geometry), "cameras[1].orientation[0]");

  ubersim::field_geometry_t field = dds_test::field_geometry();
  field.ball_radius = kInf;
  EXPECT_EQ(dds::non_finite_field(field), "ball_radius");

  ubersim::radio_feedback_t feedback = dds_test::radio_feedback(0);
  feedback.t_sent = kNaN;
  EXPECT_FALSE(dds::admit(feedback).forward);

  ubersim::sim_control_ack_t ack = dds_test::sim_control_ack(1);
  EXPECT_TRUE(dds::admit(ack).forward);
  ack.sim_time = kNaN;
  EXPECT_FALSE(dds::admit(ack).forward);
}
