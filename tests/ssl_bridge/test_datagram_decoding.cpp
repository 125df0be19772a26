// decode_datagram: real messages pass, every limit refuses what exceeds it.
#include <gtest/gtest.h>
#include <ssl_simulation_control.pb.h>
#include <ssl_simulation_robot_control.pb.h>

#include <ubersim/vision_geometry_t.hpp>

#include "ubersim/field_config.hpp"
#include "ubersim/ssl_bridge/datagram_decoding.hpp"
#include "ubersim/ssl_bridge/vision_translation.hpp"

using namespace ubersim::ssl;

namespace {

DecodedDatagram decode(const std::string& bytes, google::protobuf::Message& message,
                       Errors& errors) {
  return decode_datagram(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size(), message,
                         errors);
}

}  // namespace

TEST(SslDatagramDecoding, TheFieldAsTheBridgeSendsItDecodes) {
  ubersim::vision_geometry_t geometry{};
  geometry.field =
      ubersim::load_field_config(UBERSIM_SOURCE_CONFIG_DIR, "division_a").to_message(0.0215);
  SimulatorCommand command;
  *command.mutable_config()->mutable_geometry() = geometry_packet(geometry, {}).geometry();
  SimulatorCommand decoded;
  Errors errors;
  EXPECT_TRUE(decode(command.SerializeAsString(), decoded, errors).ok);
  EXPECT_TRUE(errors.empty());
  EXPECT_EQ(decoded.config().geometry().field().field_lines_size(),
            command.config().geometry().field().field_lines_size());
}

TEST(SslDatagramDecoding, ANestedLengthBeyondTheDatagramIsMalformed) {
  // SimulatorCommand.control (field 1) of 6 bytes holding teleport_ball
  // (field 1) whose unknown field 20 claims 64 MB.
  const std::string bytes("\x0a\x06\x0a\x04\xa2\x01\x80\x80", 8);
  SimulatorCommand command;
  Errors errors;
  EXPECT_FALSE(decode(bytes, command, errors).ok);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].code(), kErrorMalformed);
}

TEST(SslDatagramDecoding, SixtyFiveCommandsAreTooMany) {
  RobotControl control;
  for (int i = 0; i < kMaxRepeatedElements + 1; ++i) {
    control.add_robot_commands()->set_id(static_cast<std::uint32_t>(i));
  }
  RobotControl decoded;
  Errors errors;
  EXPECT_FALSE(decode(control.SerializeAsString(), decoded, errors).ok);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0].code(), kErrorTooLarge);
  control.mutable_robot_commands()->RemoveLast();
  errors.clear();
  EXPECT_TRUE(decode(control.SerializeAsString(), decoded, errors).ok);
  EXPECT_EQ(decoded.robot_commands_size(), kMaxRepeatedElements);
}
