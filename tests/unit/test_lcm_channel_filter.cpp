// The kernel-side LCM channel filter, attached to a real UDP socket on the
// loopback interface: datagrams in LCM's wire format that the program must
// keep or drop, sent through the real kernel.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <string>
#include <vector>

#include "ubersim/lcm_channel_filter.hpp"
#include "ubersim/lcm_udpm_receiver.hpp"

namespace {

class Socket {
 public:
  Socket() : fd_(::socket(AF_INET, SOCK_DGRAM, 0)) {}
  ~Socket() { ::close(fd_); }
  Socket(const Socket&) = delete;
  Socket& operator=(const Socket&) = delete;
  int fd() const { return fd_; }

 private:
  int fd_;
};

// Every filter these tests attach keeps it.
const std::string kMarker = "END";

std::string short_message(const std::string& channel, const std::string& payload) {
  return std::string("LC02") + std::string("\0\0\0\7", 4) + channel + std::string(1, '\0') +
         payload;
}

class ChannelFilter : public ::testing::Test {
 protected:
  void SetUp() override {
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ASSERT_EQ(::bind(receiver_.fd(), reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
    socklen_t size = sizeof address_;
    ASSERT_EQ(::getsockname(receiver_.fd(), reinterpret_cast<sockaddr*>(&address_), &size), 0);
  }

  void send(const std::string& datagram) {
    ASSERT_EQ(::sendto(sender_.fd(), datagram.data(), datagram.size(), 0,
                       reinterpret_cast<const sockaddr*>(&address_), sizeof address_),
              static_cast<ssize_t>(datagram.size()));
  }

  // Everything the socket got, up to the end marker (accepted by every filter
  // these tests attach, and sent last: one socket keeps the order).
  std::vector<std::string> received_until_marker() {
    send(short_message(kMarker, "end"));
    std::vector<std::string> received;
    char buffer[70000];
    for (;;) {
      pollfd ready{receiver_.fd(), POLLIN, 0};
      if (::poll(&ready, 1, 5000) != 1) {
        ADD_FAILURE() << "the end marker did not arrive";
        return received;
      }
      const ssize_t size = ::recv(receiver_.fd(), buffer, sizeof buffer, 0);
      if (size < 0) continue;
      const std::string datagram(buffer, static_cast<std::size_t>(size));
      if (datagram == short_message(kMarker, "end")) return received;
      received.push_back(datagram);
    }
  }

  Socket sender_;
  Socket receiver_;
  sockaddr_in address_{};
};

TEST_F(ChannelFilter, KeepsExactlyTheSubscribedChannelsAndEveryFragment) {
  const std::string long_name(63, 'L');
  ASSERT_TRUE(ubersim::attach_lcm_channel_filter(receiver_.fd(),
                                                 {"A", "ABCDE", "VISION", long_name, kMarker}));
  const std::vector<std::string> kept{
      short_message("A", ""),       // a name of one byte, nothing after its NUL
      short_message("ABCDE", "x"),  // 6 bytes with the NUL: a word and a half word
      short_message("VISION", std::string(3000, 'v')),
      short_message(long_name, "payload"),
      std::string("LC03") + std::string(16, '\1'),  // a fragment: kept, LCM decides
  };
  const std::vector<std::string> dropped{
      short_message("AB", ""),     // a longer name that starts like a kept one
      short_message("ABCD", "E"),  // a shorter one; its payload spells the rest
      short_message("VISIONX", ""),
      short_message("VISIO", "N"),
      short_message("vision", ""),
      short_message(long_name + "L", ""),
      "LC02",  // too short to hold a channel
      "LC0",
      "",
      "hello, not LCM at all",
      std::string("LC01") + std::string(12, 'A'),
  };
  for (const std::string& datagram : dropped) send(datagram);
  for (const std::string& datagram : kept) send(datagram);
  EXPECT_EQ(received_until_marker(), kept);
}

TEST_F(ChannelFilter, AnEmptySetKeepsOnlyFragments) {
  ASSERT_TRUE(ubersim::attach_lcm_channel_filter(receiver_.fd(), {}));
  send(short_message("SIM_STATE", "s"));
  send(std::string("LC03") + std::string(16, '\2'));
  ASSERT_TRUE(ubersim::attach_lcm_channel_filter(receiver_.fd(), {kMarker}));
  EXPECT_EQ(received_until_marker(),
            std::vector<std::string>{std::string("LC03") + std::string(16, '\2')});
}

TEST_F(ChannelFilter, DetachingLetsEverythingThrough) {
  ASSERT_TRUE(ubersim::attach_lcm_channel_filter(receiver_.fd(), {"A", kMarker}));
  ubersim::detach_lcm_channel_filter(receiver_.fd());
  send(short_message("B", ""));
  send("junk");
  EXPECT_EQ(received_until_marker(), (std::vector<std::string>{short_message("B", ""), "junk"}));
}

TEST(ChannelNames, RegularExpressionsAreNotPlainNames) {
  EXPECT_TRUE(ubersim::is_plain_channel_name("RADIO_BLUE"));
  EXPECT_TRUE(ubersim::is_plain_channel_name("game-1/SIM_STATE"));
  EXPECT_FALSE(ubersim::is_plain_channel_name(".*"));
  EXPECT_FALSE(ubersim::is_plain_channel_name("RADIO_(BLUE|YELLOW)"));
  EXPECT_FALSE(ubersim::is_plain_channel_name("game.1_VISION"));
  EXPECT_FALSE(ubersim::is_plain_channel_name(""));
  EXPECT_FALSE(ubersim::is_plain_channel_name(std::string(64, 'A')));
}

}  // namespace

namespace {

TEST(LcmUrls, TheAddressOfUdpmUrlsOnly) {
  const auto address =
      ubersim::parse_lcm_udpm_url("udpm://239.255.76.67:7791?ttl=0&recv_buf_size=4194304");
  ASSERT_TRUE(address);
  EXPECT_EQ(address->group, "239.255.76.67");
  EXPECT_EQ(address->port, 7791);
  EXPECT_EQ(address->receive_buffer_bytes, 4194304);
  EXPECT_EQ(ubersim::parse_lcm_udpm_url("udpm://239.255.76.67:7667")->receive_buffer_bytes, 0);
  EXPECT_FALSE(ubersim::parse_lcm_udpm_url("memq://"));
  EXPECT_FALSE(ubersim::parse_lcm_udpm_url("file:///tmp/x.lcmlog?speed=0"));
  EXPECT_FALSE(ubersim::parse_lcm_udpm_url("udpm://239.255.76.67:99999"));
}

}  // namespace
