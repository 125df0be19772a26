#pragma once
// Which process holds a UDP socket: what tells the bridge which team program
// sent a datagram (team_group.hpp, program_of_port).
#include <sys/types.h>

#include <cstdint>
#include <string>
#include <vector>

namespace ubersim::ssl {

// The inodes of the UDP sockets (IPv4 and IPv6) of this network namespace
// bound to local `port`, as /proc/net/udp and /proc/net/udp6 list them.
std::vector<unsigned long> udp_socket_inodes(std::uint16_t port);
// The same from the text of such a file.
std::vector<unsigned long> udp_socket_inodes(const std::string& table, std::uint16_t port);
// Whether process pid has one of these sockets open (its /proc/<pid>/fd).
bool holds_socket(pid_t pid, const std::vector<unsigned long>& inodes);

}  // namespace ubersim::ssl
