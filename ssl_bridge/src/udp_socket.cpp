#include "ubersim/ssl_bridge/udp_socket.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <utility>

namespace ubersim::ssl {
namespace {

int open_socket() {
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd < 0) throw std::runtime_error(std::string("socket: ") + std::strerror(errno));
  return fd;
}

[[noreturn]] void fail(int fd, const std::string& what) {
  const std::string reason = std::strerror(errno);
  ::close(fd);
  throw std::runtime_error(what + ": " + reason);
}

}  // namespace

sockaddr_in make_address(const std::string& ip, int port) {
  if (port <= 0 || port > 65535)
    throw std::invalid_argument("port out of range: " + std::to_string(port));
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<uint16_t>(port));
  if (::inet_pton(AF_INET, ip.c_str(), &address.sin_addr) != 1) {
    throw std::invalid_argument("not an IPv4 address: " + ip);
  }
  return address;
}

UdpSocket UdpSocket::bound(const std::string& ip, int port) {
  const sockaddr_in address = make_address(ip, port);
  const int fd = open_socket();
  // No SO_REUSEADDR nor SO_REUSEPORT: with them Linux lets a second bridge
  // (or grSim) bind the same port and splits the datagrams between the two
  // without a word. Without them the second bind fails, and says why.
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
    if (errno == EADDRINUSE) {
      ::close(fd);
      throw std::runtime_error(
          "UDP " + ip + ":" + std::to_string(port) +
          " is already in use by another program (a second simulator: another ubersim SSL "
          "bridge, grSim or the ER-Force simulator?); stop it, or run beside it on other ports "
          "(ubersim_ssl_bridge --help names them; tools/launch.sh --ssl-port-offset N)");
    }
    fail(fd, "bind " + ip + ":" + std::to_string(port));
  }
  return UdpSocket(fd);
}

UdpSocket UdpSocket::multicast_sender(int ttl, const std::string& interface_ip) {
  const in_addr interface_address = make_address(interface_ip, 1).sin_addr;
  const int fd = open_socket();
  const unsigned char ttl_byte = static_cast<unsigned char>(ttl);
  const unsigned char loop = 1;  // receivers on this host (the usual case) hear it
  if (::setsockopt(fd, IPPROTO_IP, IP_MULTICAST_TTL, &ttl_byte, sizeof ttl_byte) != 0 ||
      ::setsockopt(fd, IPPROTO_IP, IP_MULTICAST_LOOP, &loop, sizeof loop) != 0) {
    fail(fd, "multicast options");
  }
  if (::setsockopt(fd, IPPROTO_IP, IP_MULTICAST_IF, &interface_address, sizeof interface_address) !=
      0) {
    fail(fd, "multicast interface " + interface_ip);
  }
  return UdpSocket(fd);
}

UdpSocket UdpSocket::multicast_receiver(const std::string& group, int port,
                                        const std::vector<std::string>& interface_ips,
                                        std::vector<std::string>& failed_joins) {
  const sockaddr_in address = make_address(group, port);
  const int fd = open_socket();
  const int yes = 1;
  if (::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes) != 0) fail(fd, "SO_REUSEADDR");
  // Bound to the group's address, the socket hears that group only, not every
  // group another program uses on the same port.
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
    fail(fd, "bind " + group + ":" + std::to_string(port));
  }
  if (!IN_MULTICAST(ntohl(address.sin_addr.s_addr))) return UdpSocket(fd);
  std::size_t joined = 0;
  for (const std::string& interface_ip : interface_ips) {
    ip_mreq membership{};
    membership.imr_multiaddr = address.sin_addr;
    membership.imr_interface = make_address(interface_ip, 1).sin_addr;
    if (::setsockopt(fd, IPPROTO_IP, IP_ADD_MEMBERSHIP, &membership, sizeof membership) == 0) {
      ++joined;
    } else {
      failed_joins.push_back("join " + group + " on " + interface_ip + ": " + std::strerror(errno));
    }
  }
  if (joined == 0) fail(fd, "join " + group + " on no interface");
  return UdpSocket(fd);
}

UdpSocket::UdpSocket(UdpSocket&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}

UdpSocket& UdpSocket::operator=(UdpSocket&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = std::exchange(other.fd_, -1);
  }
  return *this;
}

UdpSocket::~UdpSocket() {
  if (fd_ >= 0) ::close(fd_);
}

std::optional<std::vector<uint8_t>> UdpSocket::receive(sockaddr_in& from) {
  std::vector<uint8_t> buffer(65536);
  socklen_t length = sizeof from;
  const ssize_t size =
      ::recvfrom(fd_, buffer.data(), buffer.size(), 0, reinterpret_cast<sockaddr*>(&from), &length);
  if (size < 0) return std::nullopt;
  buffer.resize(static_cast<size_t>(size));
  return buffer;
}

bool UdpSocket::send_to(const std::string& bytes, const sockaddr_in& to) {
  return ::sendto(fd_, bytes.data(), bytes.size(), 0, reinterpret_cast<const sockaddr*>(&to),
                  sizeof to) == static_cast<ssize_t>(bytes.size());
}

}  // namespace ubersim::ssl
