#pragma once
// Where the bridge's SSL multicast streams (vision, tracked frames, Referee
// messages) go, and the sockets that send them.
//
// By default a stream leaves on two interfaces:
//   * the one the kernel routes the group to ("default": on a desktop the
//     interface of the default route), with TTL 1 as grSim and ssl-vision send,
//     so a program that joins on 0.0.0.0 or on that interface's address hears
//     it, on this host (multicast loopback) and on the local network;
//   * lo (127.0.0.1), for a program that joins on 127.0.0.1 only.
// A listener on this host must not hear every packet twice. Linux hands a
// datagram that arrives on any interface where the host joined the group to
// every socket bound to the group's port (IP_MULTICAST_ALL, on by default),
// whichever interface that socket joined on; so while someone on this host
// joined the group on the default interface, its looped-back copy already
// reaches every local listener and the lo copy is not sent. The lo copy
// serves a host where nobody joined on the default interface (a listener
// joined on 127.0.0.1 alone). Who joined where is read from /proc/net/igmp,
// at most once a second.
#include <netinet/in.h>

#include <chrono>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "ubersim/ssl_bridge/udp_socket.hpp"

namespace ubersim::ssl {

// The word for "the interface the kernel routes the group to" in an interface list.
inline constexpr const char* kDefaultInterface = "default";

// One multicast stream's settings, as the command line gives them.
struct StreamSettings {
  std::string name;   // "vision", "tracked frames", "referee": for the log
  std::string group;  // multicast group (or a unicast address: sent there once)
  int port = 0;
  int ttl = 1;
  // Comma-separated interface addresses, or "default" (see above).
  std::string interfaces = std::string(kDefaultInterface) + ",127.0.0.1";
};

// One interface a stream leaves on.
struct OutInterface {
  std::string address;  // IPv4 address of the interface
  std::string device;   // its name (e.g. eth0, lo), "?" when no interface has that address
  bool routed = false;  // the interface the kernel routes the group to ("default")
  bool loopback() const { return device == "lo" || address.rfind("127.", 0) == 0; }
};

// The interface the kernel would pick for `group`: what a join on 0.0.0.0
// joins, and where a sender without IP_MULTICAST_IF sends. nullopt when there
// is no route to the group (then `why` says so).
std::optional<OutInterface> route_interface(const std::string& group, std::string& why);
// The device of the longest-prefix route to `group` in a /proc/net/route
// table ("" when none matches).
std::string route_device(const std::string& group, const std::string& routes);
// The first IPv4 address of `device` ("" when it has none).
std::string interface_address(const std::string& device);
// The name of the interface holding `address` ("?" when none does).
std::string interface_name(const std::string& address);
// "default,127.0.0.1" -> the interfaces, "default" resolved, duplicates merged.
// Throws std::invalid_argument naming an entry that is not an IPv4 address.
std::vector<OutInterface> resolve_interfaces(const std::string& list, const std::string& group,
                                             std::vector<std::string>& warnings);

// Which interfaces have joined which groups (/proc/net/igmp).
class GroupMemberships {
 public:
  explicit GroupMemberships(std::string path = "/proc/net/igmp") : path_(std::move(path)) {}
  // Reads the table again; a file that cannot be read leaves it empty.
  void refresh();
  // Parses the text of /proc/net/igmp.
  void parse(const std::string& text);
  bool joined(const std::string& device, const std::string& group) const;

 private:
  std::string path_;
  std::map<std::string, std::vector<std::uint32_t>> groups_by_device_;  // raw network order
};

// Sends one stream's datagrams on each of its interfaces.
class MulticastStream {
 public:
  explicit MulticastStream(const StreamSettings& settings);

  // False when a send failed on an interface it was meant for.
  bool send(const std::string& bytes);
  // The vision port can change at run time (simulation protocol).
  void set_port(int port);
  // One line for the log: group:port, interfaces, TTL, and who hears it.
  std::string describe() const;
  const std::vector<OutInterface>& interfaces() const { return interfaces_; }
  const std::vector<std::string>& warnings() const { return warnings_; }
  // Datagrams not sent on lo because a listener joined on another interface.
  std::uint64_t loopback_copies_skipped() const { return loopback_skipped_; }

 private:
  // The lo copy is needed unless the group is joined on a non-lo interface it is sent on.
  bool loopback_copy_needed(std::chrono::steady_clock::time_point now);

  StreamSettings settings_;
  sockaddr_in destination_{};
  bool multicast_ = true;
  std::vector<OutInterface> interfaces_;
  std::vector<UdpSocket> sockets_;  // one per interface, same order
  std::vector<std::string> warnings_;
  GroupMemberships memberships_;
  std::chrono::steady_clock::time_point memberships_read_{};
  bool loopback_needed_ = true;
  std::uint64_t loopback_skipped_ = 0;
};

}  // namespace ubersim::ssl
