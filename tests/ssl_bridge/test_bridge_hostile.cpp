// The real ubersim_ssl_bridge process against hostile datagrams on its three
// UDP ports: 64 KB datagrams, huge repeated fields, deep nesting, unknown
// fields, a flood of control commands. Each is answered with an error code,
// counted and logged once; memory stays bounded; the bridge keeps working and
// stops on SIGINT within a second. ISOLATED: own network namespace.
#include <gtest/gtest.h>

#include <chrono>
#include <random>
#include <regex>
#include <thread>
#include <ubersim/radio_packet_t.hpp>

#include "child_process.hpp"
#include "process_memory.hpp"
#include "ssl_client.hpp"
#include "ubersim/common_options.hpp"
#include "ubersim/message_bus.hpp"

namespace {

using ubersim::test::ChildProcess;
using ubersim::test::resident_kilobytes;

bool has_code(const google::protobuf::RepeatedPtrField<SimulatorError>& errors,
              const std::string& code) {
  for (const SimulatorError& error : errors) {
    if (error.code() == code) return true;
  }
  return false;
}

int count_of(const std::string& text, const std::string& what) {
  int count = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++count;
  return count;
}

// 15,000 robot commands holding only an id: 60 KB of bytes, 15,000 elements.
std::string huge_robot_control() {
  std::string bytes;
  for (int i = 0; i < 15000; ++i) bytes += std::string("\x0a\x02\x08\x01", 4);
  return bytes;
}

// A group field the protocol lacks, nested `depth` times (start-group tags of
// field 100, then as many end-group tags).
std::string nested_groups(int depth) {
  std::string bytes;
  for (int i = 0; i < depth; ++i) bytes += "\xa3\x06";
  for (int i = 0; i < depth; ++i) bytes += "\xa4\x06";
  return bytes;
}

class SslBridgeHostile : public ::testing::Test {
 protected:
  void SetUp() override {
    std::vector<std::string> argv{UBERSIM_SSL_BRIDGE_EXE, "--ack-timeout", "1"};
    for (const std::string& option : ports_.bridge_options()) argv.push_back(option);
    bridge_ = std::make_unique<ChildProcess>(argv, ::testing::TempDir() + "ssl_bridge_hostile.log");
    ASSERT_TRUE(bridge_->wait_for_output("vision to", 10)) << bridge_->log();
    bus_.subscribe<ubersim::radio_packet_t>(
        "RADIO_BLUE", [this](const ubersim::radio_packet_t& p) { radio_blue_.push_back(p); });
  }

  // Stops the bridge with SIGINT, expects a clean exit within 1 s, returns its log.
  std::string stop_within_a_second() {
    const auto start = std::chrono::steady_clock::now();
    EXPECT_EQ(bridge_->stop(5, SIGINT), 0) << bridge_->log();
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_LT(seconds, 1.0);
    std::string log = bridge_->log();
    bridge_.reset();
    return log;
  }

  const ssl_test::TestPorts ports_ = ssl_test::TestPorts::from_environment();
  ubersim::MessageBus bus_{ubersim::with_receive_buffer(ubersim::default_lcm_url())};
  std::unique_ptr<ChildProcess> bridge_;
  std::vector<ubersim::radio_packet_t> radio_blue_;
};

}  // namespace

TEST_F(SslBridgeHostile, OversizedNestedAndHugeDatagramsAreRefusedWithBoundedMemory) {
  ssl_test::UdpClient control_port(ports_.control);
  ssl_test::UdpClient blue(ports_.blue);
  ssl_test::UdpClient yellow(ports_.yellow);
  const long rss_before = resident_kilobytes(bridge_->pid());

  // Huge repeated field: refused as a whole, nothing reaches the radio.
  blue.send(huge_robot_control());
  auto bytes = blue.receive(3);
  ASSERT_TRUE(bytes.has_value()) << bridge_->log();
  RobotControlResponse robot_response;
  ASSERT_TRUE(robot_response.ParseFromString(*bytes));
  EXPECT_TRUE(has_code(robot_response.errors(), "UBERSIM_TOO_LARGE"))
      << robot_response.DebugString();

  SimulatorCommand many_robots;
  for (int i = 0; i < 2000; ++i) {
    many_robots.mutable_control()->add_teleport_robot()->mutable_id()->set_id(1);
  }
  const auto control_response = ssl_test::command(control_port, many_robots);
  ASSERT_TRUE(control_response.has_value());
  EXPECT_TRUE(has_code(control_response->errors(), "UBERSIM_TOO_LARGE"));

  // Deep nesting (20,000 groups in 80 KB would not fit: 16,000 in 64 KB).
  yellow.send(nested_groups(16000));
  bytes = yellow.receive(3);
  ASSERT_TRUE(bytes.has_value());
  ASSERT_TRUE(robot_response.ParseFromString(*bytes));
  EXPECT_TRUE(has_code(robot_response.errors(), "UBERSIM_MALFORMED"));

  // The largest datagram UDP carries, random bytes, on every port, 500 times.
  std::mt19937 random(2026);
  std::string big(65507, '\0');
  for (int i = 0; i < 500; ++i) {
    for (char& byte : big) byte = static_cast<char>(random() & 0xff);
    ssl_test::UdpClient& port = i % 3 == 0 ? control_port : (i % 3 == 1 ? blue : yellow);
    port.send(big);
    ASSERT_TRUE(port.receive(3).has_value()) << "64 KB datagram " << i << " not answered";
  }
  // Deeply nested but within the limit, huge repeated fields: 500 more.
  for (int i = 0; i < 500; ++i) {
    blue.send(i % 2 == 0 ? huge_robot_control() : nested_groups(10 + i));
    ASSERT_TRUE(blue.receive(3).has_value());
  }
  const long rss_after = resident_kilobytes(bridge_->pid());
  std::printf("bridge resident memory: %ld kB before, %ld kB after 1,000 hostile datagrams\n",
              rss_before, rss_after);
  EXPECT_LT(rss_after - rss_before, 20 * 1024);

  // Still working.
  RobotControl control;
  control.add_robot_commands()->set_id(6);
  const auto response = ssl_test::control(blue, control);
  ASSERT_TRUE(response.has_value());
  EXPECT_EQ(response->errors_size(), 0) << response->DebugString();
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (radio_blue_.empty() && std::chrono::steady_clock::now() < deadline) {
    bus_.wait_and_handle(20);
  }
  ASSERT_EQ(radio_blue_.size(), 1u) << "only the valid command reaches the radio";
  EXPECT_EQ(radio_blue_[0].num_commands, 1);

  const std::string log = stop_within_a_second();
  EXPECT_NE(log.find("blue robot control datagrams dropped (malformed or too large)="),
            std::string::npos)
      << log;
}

TEST_F(SslBridgeHostile, UnknownFieldsAreCountedLoggedOnceAndDropped) {
  ssl_test::UdpClient blue(ports_.blue);
  RobotControl control;
  RobotCommand* command = control.add_robot_commands();
  command->set_id(4);
  MoveLocalVelocity* velocity = command->mutable_move_command()->mutable_local_velocity();
  velocity->set_forward(1.0f);
  velocity->set_left(0.0f);
  velocity->set_angular(0.0f);
  // Field 100 at the top and field 90 inside the command: both unknown.
  std::string command_bytes = command->SerializeAsString() + std::string("\xd0\x05\x07", 3);
  std::string datagram = "\x0a" + std::string(1, static_cast<char>(command_bytes.size())) +
                         command_bytes + std::string("\xa0\x06\x01", 3);
  for (int i = 0; i < 50; ++i) {
    blue.send(datagram);
    const auto bytes = blue.receive(3);
    ASSERT_TRUE(bytes.has_value());
    RobotControlResponse response;
    ASSERT_TRUE(response.ParseFromString(*bytes));
    ASSERT_EQ(response.errors_size(), 1);
    EXPECT_EQ(response.errors(0).code(), "UBERSIM_UNKNOWN_FIELDS");
    EXPECT_NE(response.errors(0).message().find("2 field(s)"), std::string::npos)
        << response.errors(0).message();
  }
  // The known part still applies: every datagram became a radio command.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (radio_blue_.size() < 50 && std::chrono::steady_clock::now() < deadline) {
    bus_.wait_and_handle(20);
  }
  ASSERT_EQ(radio_blue_.size(), 50u);
  EXPECT_EQ(radio_blue_.back().commands.at(0).robot_id, 4);
  EXPECT_DOUBLE_EQ(radio_blue_.back().commands.at(0).vx, 1.0);

  const std::string log = stop_within_a_second();
  EXPECT_LE(count_of(log, "dropped fields ubersim does not know"), 2) << log;
  EXPECT_NE(log.find("blue robot control unknown fields dropped=100"), std::string::npos) << log;
}

TEST_F(SslBridgeHostile, AControlFloodIsAnsweredBusyAndStaysBounded) {
  // No physics: every command waits for its acknowledgement (1 s) until the
  // bridge has 256 requests waiting; later ones are answered busy at once.
  ssl_test::UdpClient control_port(ports_.control);
  SimulatorCommand pause;
  pause.mutable_control()->set_simulation_speed(0.0f);
  const std::string bytes = pause.SerializeAsString();
  const long rss_before = resident_kilobytes(bridge_->pid());
  for (int i = 0; i < 3000; ++i) control_port.send(bytes);
  int busy = 0;
  int answers = 0;
  while (auto answer = control_port.receive(2)) {
    ++answers;
    SimulatorResponse response;
    ASSERT_TRUE(response.ParseFromString(*answer));
    if (has_code(response.errors(), "UBERSIM_BUSY")) ++busy;
  }
  const long rss_after = resident_kilobytes(bridge_->pid());
  std::printf("control flood: %d answers, %d busy; resident memory %ld kB -> %ld kB\n", answers,
              busy, rss_before, rss_after);
  EXPECT_GT(busy, 0);
  EXPECT_LT(rss_after - rss_before, 20 * 1024);
  const std::string log = stop_within_a_second();
  EXPECT_NE(log.find("control datagrams refused (busy)="), std::string::npos) << log;
}
