#pragma once
// A non-blocking IPv4 UDP socket that closes itself (RAII).
#include <netinet/in.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace ubersim::ssl {

sockaddr_in make_address(const std::string& ip, int port);  // throws std::invalid_argument

class UdpSocket {
 public:
  // Bound to ip:port, for receiving requests and answering them.
  static UdpSocket bound(const std::string& ip, int port);
  // For sending to a multicast group: TTL, loopback delivery, and the
  // interface (by its address) the datagrams leave on.
  static UdpSocket multicast_sender(int ttl, const std::string& interface_ip);
  // For receiving what is sent to a multicast group and port, joined on the
  // interfaces with these addresses. Shared (SO_REUSEADDR): the teams'
  // programs listen there too. A join that fails is named in failed_joins;
  // throws when none succeeds.
  static UdpSocket multicast_receiver(const std::string& group, int port,
                                      const std::vector<std::string>& interface_ips,
                                      std::vector<std::string>& failed_joins);

  UdpSocket(UdpSocket&& other) noexcept;
  UdpSocket& operator=(UdpSocket&& other) noexcept;
  UdpSocket(const UdpSocket&) = delete;
  UdpSocket& operator=(const UdpSocket&) = delete;
  ~UdpSocket();

  int fd() const { return fd_; }
  // One datagram if one is waiting (non-blocking); nullopt when none.
  std::optional<std::vector<uint8_t>> receive(sockaddr_in& from);
  bool send_to(const std::string& bytes, const sockaddr_in& to);

 private:
  explicit UdpSocket(int fd) : fd_(fd) {}
  int fd_ = -1;
};

}  // namespace ubersim::ssl
