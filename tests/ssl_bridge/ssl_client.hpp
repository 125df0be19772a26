#pragma once
// A minimal SSL client for tests, written against the published protocol
// only: raw UDP sockets and the generated protobuf classes, as a team's
// software would use them (no code of the bridge).
#include <messages_robocup_ssl_wrapper.pb.h>
#include <ssl_simulation_control.pb.h>
#include <ssl_simulation_robot_control.pb.h>
#include <ssl_simulation_robot_feedback.pb.h>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace ssl_test {

// The ports a test uses. In its own network namespace any would do; without
// one (run_isolated.sh's fallback) each test binary must keep to ports of its
// own, so they follow the LCM port run_isolated.sh derived from the test name.
struct TestPorts {
  int vision = 10020;
  int control = 10300;
  int blue = 10301;
  int yellow = 10302;
  int referee = 10003;
  int grsim = 20011;
  int grsim_blue_status = 30011;
  int grsim_yellow_status = 30012;
  static TestPorts from_environment();              // LCM port + 1 .. + 8
  std::vector<std::string> bridge_options() const;  // --vision-port ... for the bridge
};

// Joins the SSL-Vision multicast group on the loopback interface.
class VisionReceiver {
 public:
  explicit VisionReceiver(const std::string& group = "224.5.23.2", int port = 10020);
  ~VisionReceiver();
  VisionReceiver(const VisionReceiver&) = delete;
  VisionReceiver& operator=(const VisionReceiver&) = delete;
  // The next packet that decodes, or nullopt after timeout_s.
  std::optional<SSL_WrapperPacket> receive(double timeout_s);
  // Receives until accept() returns true for a packet; false on timeout.
  bool receive_until(const std::function<bool(const SSL_WrapperPacket&)>& accept, double timeout_s);
  int undecodable() const { return undecodable_; }
  // The next datagram as it came (e.g. a TrackerWrapperPacket), or nullopt after timeout_s.
  std::optional<std::string> receive_bytes(double timeout_s);

 private:
  int fd_ = -1;
  int undecodable_ = 0;
};

// Sends datagrams to one port on 127.0.0.1 and receives the answers.
class UdpClient {
 public:
  explicit UdpClient(int port);
  ~UdpClient();
  UdpClient(const UdpClient&) = delete;
  UdpClient& operator=(const UdpClient&) = delete;
  void send(const std::string& bytes);
  std::optional<std::string> receive(double timeout_s);

 private:
  int fd_ = -1;
  int port_;
};

// A UDP socket bound to 127.0.0.1:port (0: any free port), as a team's
// software has one: it sends to the bridge's ports and receives what the
// bridge sends to its address (grSim's robot status on 30011 / 30012).
class UdpEndpoint {
 public:
  explicit UdpEndpoint(int port = 0);
  ~UdpEndpoint();
  UdpEndpoint(const UdpEndpoint&) = delete;
  UdpEndpoint& operator=(const UdpEndpoint&) = delete;
  void send(int port, const std::string& bytes) const;
  std::optional<std::string> receive(double timeout_s) const;

 private:
  int fd_ = -1;
};

// One datagram to a multicast group on the loopback interface (TTL 0), as the
// game controller sends its Referee messages.
void send_to_group(const std::string& group, int port, const std::string& bytes);

std::optional<SimulatorResponse> command(UdpClient& client, const SimulatorCommand& request,
                                         double timeout_s = 3);
std::optional<RobotControlResponse> control(UdpClient& client, const RobotControl& request,
                                            double timeout_s = 3);

// The command line of the test teams (ssl_sync_team, ssl_timed_team):
// --team yellow|blue [--vision-port P] [--port P] [--protocol ssl|grsim]; the
// port defaults to the team's robot control port (10302 yellow, 10301 blue),
// with --protocol grsim to grSim's command port (20011).
struct TeamArguments {
  bool yellow = true;
  int vision_port = 10020;
  int port = 0;
  bool grsim = false;  // commands as grSim_Packet (ssl_timed_team only)
};
// nullopt after one line on stderr naming `program` (the caller exits 2).
std::optional<TeamArguments> parse_team_arguments(int argc, char** argv, const char* program);

}  // namespace ssl_test
