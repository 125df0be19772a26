#include "ssl_client.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <iostream>
#include <stdexcept>
#include <vector>

namespace ssl_test {
namespace {

using Clock = std::chrono::steady_clock;

int remaining_ms(Clock::time_point deadline) {
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
  return left.count() < 0 ? 0 : static_cast<int>(left.count());
}

std::optional<std::string> receive_one(int fd, Clock::time_point deadline) {
  pollfd p{fd, POLLIN, 0};
  if (::poll(&p, 1, remaining_ms(deadline)) <= 0) return std::nullopt;
  std::vector<char> buffer(65536);
  const ssize_t size = ::recv(fd, buffer.data(), buffer.size(), 0);
  if (size < 0) return std::nullopt;
  return std::string(buffer.data(), static_cast<size_t>(size));
}

Clock::time_point after(double seconds) {
  return Clock::now() +
         std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
}

}  // namespace

TestPorts TestPorts::from_environment() {
  int lcm_port = 7667;  // LCM's default
  if (const char* url = std::getenv("LCM_DEFAULT_URL")) {
    const std::string text(url);
    const auto colon = text.rfind(':');
    if (colon != std::string::npos) lcm_port = std::atoi(text.c_str() + colon + 1);
  }
  TestPorts ports;
  ports.control = lcm_port + 1;
  ports.blue = lcm_port + 2;
  ports.yellow = lcm_port + 3;
  ports.vision = lcm_port + 4;
  ports.referee = lcm_port + 5;
  ports.grsim = lcm_port + 6;
  ports.grsim_blue_status = lcm_port + 7;
  ports.grsim_yellow_status = lcm_port + 8;
  return ports;
}

std::vector<std::string> TestPorts::bridge_options() const {
  return {"--vision-port",
          std::to_string(vision),
          "--control-port",
          std::to_string(control),
          "--blue-port",
          std::to_string(blue),
          "--yellow-port",
          std::to_string(yellow),
          "--referee-port",
          std::to_string(referee),
          "--grsim-port",
          std::to_string(grsim),
          "--grsim-blue-status-port",
          std::to_string(grsim_blue_status),
          "--grsim-yellow-status-port",
          std::to_string(grsim_yellow_status)};
}

VisionReceiver::VisionReceiver(const std::string& group, int port) {
  fd_ = ::socket(AF_INET, SOCK_DGRAM, 0);
  if (fd_ < 0) throw std::runtime_error("socket");
  const int one = 1;
  ::setsockopt(fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_ANY);
  if (::bind(fd_, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) {
    throw std::runtime_error("bind vision port");
  }
  ip_mreq membership{};
  ::inet_pton(AF_INET, group.c_str(), &membership.imr_multiaddr);
  ::inet_pton(AF_INET, "127.0.0.1", &membership.imr_interface);
  if (::setsockopt(fd_, IPPROTO_IP, IP_ADD_MEMBERSHIP, &membership, sizeof membership) != 0) {
    throw std::runtime_error("join vision multicast group");
  }
}

void send_to_group(const std::string& group, int port, const std::string& bytes) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  if (fd < 0) throw std::runtime_error("socket");
  const unsigned char ttl = 0;
  const unsigned char loop = 1;
  in_addr loopback{};
  ::inet_pton(AF_INET, "127.0.0.1", &loopback);
  ::setsockopt(fd, IPPROTO_IP, IP_MULTICAST_TTL, &ttl, sizeof ttl);
  ::setsockopt(fd, IPPROTO_IP, IP_MULTICAST_LOOP, &loop, sizeof loop);
  ::setsockopt(fd, IPPROTO_IP, IP_MULTICAST_IF, &loopback, sizeof loopback);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(static_cast<uint16_t>(port));
  ::inet_pton(AF_INET, group.c_str(), &to.sin_addr);
  const ssize_t sent =
      ::sendto(fd, bytes.data(), bytes.size(), 0, reinterpret_cast<sockaddr*>(&to), sizeof to);
  ::close(fd);
  if (sent != static_cast<ssize_t>(bytes.size())) throw std::runtime_error("send to group");
}

VisionReceiver::~VisionReceiver() {
  ::close(fd_);
}

std::optional<SSL_WrapperPacket> VisionReceiver::receive(double timeout_s) {
  const auto deadline = after(timeout_s);
  while (auto bytes = receive_one(fd_, deadline)) {
    SSL_WrapperPacket packet;
    if (packet.ParseFromString(*bytes)) return packet;
    ++undecodable_;
  }
  return std::nullopt;
}

std::optional<std::string> VisionReceiver::receive_bytes(double timeout_s) {
  return receive_one(fd_, after(timeout_s));
}

bool VisionReceiver::receive_until(const std::function<bool(const SSL_WrapperPacket&)>& accept,
                                   double timeout_s) {
  const auto deadline = after(timeout_s);
  while (Clock::now() < deadline) {
    const auto packet = receive(remaining_ms(deadline) / 1000.0);
    if (packet && accept(*packet)) return true;
  }
  return false;
}

UdpEndpoint::UdpEndpoint(int port) : fd_(::socket(AF_INET, SOCK_DGRAM, 0)) {
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<uint16_t>(port));
  ::inet_pton(AF_INET, "127.0.0.1", &address.sin_addr);
  if (fd_ < 0 || ::bind(fd_, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) {
    if (fd_ >= 0) ::close(fd_);
    throw std::runtime_error("cannot bind 127.0.0.1:" + std::to_string(port));
  }
}

UdpEndpoint::~UdpEndpoint() {
  ::close(fd_);
}

void UdpEndpoint::send(int port, const std::string& bytes) const {
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(static_cast<uint16_t>(port));
  ::inet_pton(AF_INET, "127.0.0.1", &to.sin_addr);
  ::sendto(fd_, bytes.data(), bytes.size(), 0, reinterpret_cast<sockaddr*>(&to), sizeof to);
}

std::optional<std::string> UdpEndpoint::receive(double timeout_s) const {
  return receive_one(fd_, after(timeout_s));
}

UdpClient::UdpClient(int port) : port_(port) {
  fd_ = ::socket(AF_INET, SOCK_DGRAM, 0);
  if (fd_ < 0) throw std::runtime_error("socket");
}

UdpClient::~UdpClient() {
  ::close(fd_);
}

void UdpClient::send(const std::string& bytes) {
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(static_cast<uint16_t>(port_));
  ::inet_pton(AF_INET, "127.0.0.1", &to.sin_addr);
  ::sendto(fd_, bytes.data(), bytes.size(), 0, reinterpret_cast<sockaddr*>(&to), sizeof to);
}

std::optional<std::string> UdpClient::receive(double timeout_s) {
  return receive_one(fd_, after(timeout_s));
}

std::optional<SimulatorResponse> command(UdpClient& client, const SimulatorCommand& request,
                                         double timeout_s) {
  client.send(request.SerializeAsString());
  const auto bytes = client.receive(timeout_s);
  SimulatorResponse response;
  if (!bytes || !response.ParseFromString(*bytes)) return std::nullopt;
  return response;
}

std::optional<RobotControlResponse> control(UdpClient& client, const RobotControl& request,
                                            double timeout_s) {
  client.send(request.SerializeAsString());
  const auto bytes = client.receive(timeout_s);
  RobotControlResponse response;
  if (!bytes || !response.ParseFromString(*bytes)) return std::nullopt;
  return response;
}

std::optional<TeamArguments> parse_team_arguments(int argc, char** argv, const char* program) {
  std::string team;
  std::string protocol = "ssl";
  TeamArguments arguments;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string option = argv[i];
    if (option == "--team") {
      team = argv[i + 1];
    } else if (option == "--vision-port") {
      arguments.vision_port = std::atoi(argv[i + 1]);
    } else if (option == "--port") {
      arguments.port = std::atoi(argv[i + 1]);
    } else if (option == "--protocol") {
      protocol = argv[i + 1];
    } else {
      std::cerr << program << ": unknown option " << option << "\n";
      return std::nullopt;
    }
  }
  if ((team != "yellow" && team != "blue") || (protocol != "ssl" && protocol != "grsim")) {
    std::cerr << "usage: " << program
              << " --team yellow|blue [--vision-port P] [--port P] [--protocol ssl|grsim]\n";
    return std::nullopt;
  }
  arguments.yellow = team == "yellow";
  arguments.grsim = protocol == "grsim";
  if (arguments.port == 0)
    arguments.port = arguments.grsim ? 20011 : arguments.yellow ? 10302 : 10301;
  return arguments;
}

}  // namespace ssl_test
