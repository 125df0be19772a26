// What a timed team sends that changes the field is held for the next frame
// and released by program, then in arrival order (held_for_next_frame.hpp);
// the program is found from the sending socket (socket_owner.hpp).
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <map>
#include <string>
#include <vector>

#include "ubersim/ssl_bridge/held_for_next_frame.hpp"
#include "ubersim/ssl_bridge/socket_owner.hpp"

using ubersim::ssl::HeldForNextFrame;

namespace {

sockaddr_in local(std::uint16_t port) {
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(port);
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  return address;
}

}  // namespace

TEST(HeldForNextFrame, ReleasesByProgramThenInArrivalOrder) {
  HeldForNextFrame<std::string> held;
  // Arrival: blue's first, yellow's, blue's second (the kernel's interleaving).
  ASSERT_TRUE(held.hold("blue 1", local(5001)));
  ASSERT_TRUE(held.hold("yellow 1", local(5000)));
  ASSERT_TRUE(held.hold("outsider", local(6000)));
  ASSERT_TRUE(held.hold("blue 2", local(5001)));
  ASSERT_TRUE(held.hold("yellow 2", local(5000)));
  const std::map<std::uint16_t, std::size_t> program{{5000, 0}, {5001, 1}, {6000, 2}};
  std::vector<std::string> applied;
  held.release([&](const sockaddr_in& from) { return program.at(ntohs(from.sin_port)); },
               [&](const std::string& item, const sockaddr_in&) { applied.push_back(item); });
  EXPECT_EQ(applied,
            (std::vector<std::string>{"yellow 1", "yellow 2", "blue 1", "blue 2", "outsider"}));
  applied.clear();
  held.release([](const sockaddr_in&) { return std::size_t{0}; },
               [&](const std::string& item, const sockaddr_in&) { applied.push_back(item); });
  EXPECT_TRUE(applied.empty());  // released once
}

TEST(HeldForNextFrame, RefusesBeyondItsBoundSoThatTheCallerAppliesAtOnce) {
  HeldForNextFrame<int> held;
  for (std::size_t i = 0; i < HeldForNextFrame<int>::kMost; ++i) {
    ASSERT_TRUE(held.hold(static_cast<int>(i), local(5000)));
  }
  EXPECT_FALSE(held.hold(-1, local(5000)));
}

TEST(SocketOwner, ReadsTheInodesOfAPortFromTheKernelsTable) {
  const std::string table =
      "   sl  local_address rem_address   st tx_queue rx_queue tr tm->when retrnsmt   uid  "
      "timeout inode ref pointer drops\n"
      "  100: 0100007F:4E21 00000000:0000 07 00000000:00000000 00:00000000 00000000     0        "
      "0 4242 2 0000000000000000 0\n"
      "  101: 00000000:4E22 00000000:0000 07 00000000:00000000 00:00000000 00000000     0        "
      "0 4343 2 0000000000000000 0\n";
  EXPECT_EQ(ubersim::ssl::udp_socket_inodes(table, 20001), (std::vector<unsigned long>{4242}));
  EXPECT_EQ(ubersim::ssl::udp_socket_inodes(table, 20002), (std::vector<unsigned long>{4343}));
  EXPECT_TRUE(ubersim::ssl::udp_socket_inodes(table, 20003).empty());
  EXPECT_TRUE(ubersim::ssl::udp_socket_inodes("garbage\nmore garbage\n", 20001).empty());
}

TEST(SocketOwner, FindsTheProcessThatHoldsARealSocket) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  ASSERT_GE(fd, 0);
  sockaddr_in address = local(0);  // an ephemeral port
  ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof(address)), 0);
  socklen_t length = sizeof(address);
  ASSERT_EQ(::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length), 0);
  const auto inodes = ubersim::ssl::udp_socket_inodes(ntohs(address.sin_port));
  ASSERT_EQ(inodes.size(), 1U);
  EXPECT_TRUE(ubersim::ssl::holds_socket(::getpid(), inodes));
  EXPECT_FALSE(ubersim::ssl::holds_socket(::getppid(), inodes));
  ::close(fd);
  EXPECT_FALSE(ubersim::ssl::holds_socket(::getpid(), inodes));
}
