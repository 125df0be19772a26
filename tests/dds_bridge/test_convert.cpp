// LCM <-> DDS conversions: every field of every bridged type survives the
// round trip bit for bit, and the DDS side holds the values where the IDL
// says (checked field by field for the vision frame and the radio packet).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "sample_messages.hpp"
#include "ubersim/dds_bridge/convert.hpp"
#include "ubersim/dds_bridge/echo_filter.hpp"

namespace dds = ubersim::dds;
using dds::lcm_bytes;

namespace {

// Identical LCM encodings <=> identical field values (NaN payloads included).
template <class Msg>
void expect_round_trip(const Msg& message) {
  const auto sample = dds::to_dds(message);
  const Msg back = dds::from_dds(sample.get());
  EXPECT_EQ(lcm_bytes(back), lcm_bytes(message)) << Msg::getTypeName();
}

}  // namespace

TEST(DdsConvert, EveryTypeRoundTripsUnchanged) {
  expect_round_trip(dds_test::vision_frame(17));
  expect_round_trip(dds_test::field_geometry(0.5));
  expect_round_trip(dds_test::vision_geometry(1.5));
  expect_round_trip(dds_test::radio_packet(1, 99));
  expect_round_trip(dds_test::radio_feedback(0, 2.0));
  expect_round_trip(dds_test::sim_commands(1, 5));
  expect_round_trip(dds_test::sim_state(1234));
  expect_round_trip(dds_test::sim_control(77));
  expect_round_trip(dds_test::sim_control_ack(78));
}

TEST(DdsConvert, EmptySequencesAndStringsRoundTrip) {
  expect_round_trip(dds_test::vision_frame(0, 0, 0));
  ubersim::sim_state_t state = dds_test::sim_state(1, 0);
  expect_round_trip(state);
  ubersim::radio_packet_t packet = dds_test::radio_packet(0, 1);
  packet.commands.clear();
  packet.num_commands = 0;
  expect_round_trip(packet);
  ubersim::sim_control_t control = dds_test::sim_control(1);
  control.sender.clear();
  control.robots[0].robot_type.clear();
  expect_round_trip(control);
}

TEST(DdsConvert, NonFiniteValuesCrossUnchanged) {
  // The conversion is not the place to judge values (sample_checks is).
  ubersim::vision_frame_t frame = dds_test::vision_frame(3);
  frame.balls[0].x = std::numeric_limits<double>::quiet_NaN();
  frame.robots_blue[1].orientation = std::numeric_limits<double>::infinity();
  expect_round_trip(frame);
}

TEST(DdsConvert, VisionFrameFieldsLandWhereTheIdlSays) {
  const ubersim::vision_frame_t frame = dds_test::vision_frame(42, 2, 3);
  const auto sample = dds::to_dds(frame);
  const dds::DdsVisionFrame& d = sample.get();
  EXPECT_EQ(d.camera_id, frame.camera_id);
  EXPECT_EQ(d.frame_number, frame.frame_number);
  EXPECT_EQ(d.t_capture, frame.t_capture);
  EXPECT_EQ(d.t_sent, frame.t_sent);
  ASSERT_EQ(d.balls._length, 2u);
  EXPECT_TRUE(d.balls._release);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(d.balls._buffer[i].confidence, frame.balls[i].confidence);
    EXPECT_EQ(d.balls._buffer[i].x, frame.balls[i].x);
    EXPECT_EQ(d.balls._buffer[i].y, frame.balls[i].y);
    EXPECT_EQ(d.balls._buffer[i].pixel_x, frame.balls[i].pixel_x);
    EXPECT_EQ(d.balls._buffer[i].pixel_y, frame.balls[i].pixel_y);
    EXPECT_EQ(d.balls._buffer[i].area, frame.balls[i].area);
  }
  ASSERT_EQ(d.robots_yellow._length, 3u);
  ASSERT_EQ(d.robots_blue._length, 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    const auto& y = d.robots_yellow._buffer[i];
    EXPECT_EQ(y.robot_id, frame.robots_yellow[i].robot_id);
    EXPECT_EQ(y.confidence, frame.robots_yellow[i].confidence);
    EXPECT_EQ(y.x, frame.robots_yellow[i].x);
    EXPECT_EQ(y.y, frame.robots_yellow[i].y);
    EXPECT_EQ(y.orientation, frame.robots_yellow[i].orientation);
    EXPECT_EQ(y.pixel_x, frame.robots_yellow[i].pixel_x);
    EXPECT_EQ(y.pixel_y, frame.robots_yellow[i].pixel_y);
    EXPECT_EQ(d.robots_blue._buffer[i].robot_id, frame.robots_blue[i].robot_id);
    EXPECT_EQ(d.robots_blue._buffer[i].x, frame.robots_blue[i].x);
  }
}

TEST(DdsConvert, RadioPacketFieldsLandWhereTheIdlSays) {
  const ubersim::radio_packet_t packet = dds_test::radio_packet(1, 31);
  const auto sample = dds::to_dds(packet);
  const dds::DdsRadioPacket& d = sample.get();
  EXPECT_EQ(d.team, 1);
  EXPECT_EQ(d.sequence_number, 31);
  EXPECT_EQ(d.t_sent, packet.t_sent);
  ASSERT_EQ(d.commands._length, 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    const auto& c = d.commands._buffer[i];
    const auto& l = packet.commands[i];
    EXPECT_EQ(c.robot_id, l.robot_id);
    EXPECT_EQ(c.mode, l.mode);
    EXPECT_EQ(c.vx, l.vx);
    EXPECT_EQ(c.vy, l.vy);
    EXPECT_EQ(c.omega, l.omega);
    ASSERT_EQ(c.wheel_speeds._length, l.wheel_speeds.size());
    for (std::size_t w = 0; w < l.wheel_speeds.size(); ++w)
      EXPECT_EQ(c.wheel_speeds._buffer[w], l.wheel_speeds[w]);
    EXPECT_EQ(c.kick_speed, l.kick_speed);
    EXPECT_EQ(c.chip_speed, l.chip_speed);
    EXPECT_EQ(c.chip_angle, l.chip_angle);
    EXPECT_EQ(c.dribbler_speed, l.dribbler_speed);
  }
}

TEST(DdsConvert, StringsAreOwnedCopies) {
  ubersim::field_geometry_t field = dds_test::field_geometry();
  const auto sample = dds::to_dds(field);
  field.name = "changed afterwards";
  EXPECT_STREQ(sample.get().name, "division_b");
}

TEST(DdsConvert, NullStringFromDdsReadsAsEmpty) {
  dds::DdsFieldGeometry d{};
  d.name = nullptr;
  d.field_length = 9;
  const ubersim::field_geometry_t field = dds::from_dds(d);
  EXPECT_EQ(field.name, "");
  EXPECT_EQ(field.field_length, 9);
}

TEST(DdsConvert, LcmBooleansBecomeZeroOrOne) {
  ubersim::radio_feedback_t feedback = dds_test::radio_feedback(0);
  feedback.robots[0].ball_contact = 5;  // LCM carries a boolean as a whole byte
  const auto back = dds::from_dds(dds::to_dds(feedback).get());
  EXPECT_EQ(back.robots[0].ball_contact, 1);
}

TEST(DdsConvert, CountsFollowTheSequences) {
  const auto back = dds::from_dds(dds::to_dds(dds_test::sim_state(3, 4)).get());
  EXPECT_EQ(back.num_robots, 8);
  EXPECT_EQ(back.robots[5].num_wheels, 4);
}

TEST(DdsConvert, MovedSampleOwnsItsContentsOnce) {
  auto first = dds::to_dds(dds_test::vision_frame(1));
  dds::OwnedSample<dds::DdsVisionFrame> second = std::move(first);
  EXPECT_EQ(first.get().balls._buffer, nullptr);  // NOLINT(bugprone-use-after-move)
  EXPECT_EQ(second.get().balls._length, 2u);
  first = std::move(second);
  EXPECT_EQ(first.get().balls._length, 2u);
}
