// The real ubersim_viewer process against hostile pages: WebSocket frames at
// and above the maximum message size, JSON nesting bombs, other sites' pages
// (and DNS rebinding), 200 connections at once. Each is refused or dropped,
// memory stays bounded, the viewer keeps serving its own page and stops on
// SIGINT within a second. ISOLATED: real LCM in its own network namespace.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <memory>
#include <string>
#include <ubersim/sim_control_t.hpp>
#include <vector>

#include "child_process.hpp"
#include "process_memory.hpp"
#include "ubersim/common_options.hpp"
#include "ubersim/message_bus.hpp"

namespace {

using ubersim::test::ChildProcess;
using ubersim::test::resident_kilobytes;

class Socket {
 public:
  explicit Socket(int port) {
    fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    timeval timeout{5, 0};
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<uint16_t>(port));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    connected_ = ::connect(fd_, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0;
  }
  ~Socket() { ::close(fd_); }
  Socket(const Socket&) = delete;
  Socket& operator=(const Socket&) = delete;
  bool connected() const { return connected_; }
  bool send(const std::string& bytes) {
    return ::send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL) ==
           static_cast<ssize_t>(bytes.size());
  }
  // The HTTP response head (up to the blank line), or what came before a close.
  std::string response_head() {
    std::string text;
    char c;
    while (text.find("\r\n\r\n") == std::string::npos && ::recv(fd_, &c, 1, 0) == 1) text += c;
    return text;
  }
  // Everything until the peer closes (or 5 s pass).
  std::string until_closed() {
    std::string text;
    char buffer[4096];
    ssize_t n;
    while ((n = ::recv(fd_, buffer, sizeof buffer, 0)) > 0)
      text.append(buffer, static_cast<size_t>(n));
    return text;
  }

 private:
  int fd_ = -1;
  bool connected_ = false;
};

std::string handshake(const std::string& host, const std::string& origin) {
  std::string request =
      "GET / HTTP/1.1\r\nHost: " + host +
      "\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
      "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n";
  if (!origin.empty()) request += "Origin: " + origin + "\r\n";
  return request + "\r\n";
}

bool opened(const std::string& head) {
  return head.rfind("HTTP/1.1 101", 0) == 0;
}

// A masked client text frame of any length (mask key 0).
std::string text_frame(const std::string& payload) {
  std::string frame(1, static_cast<char>(0x81));
  const uint64_t n = payload.size();
  if (n < 126) {
    frame += static_cast<char>(0x80 | n);
  } else if (n <= 0xffff) {
    frame += static_cast<char>(0x80 | 126);
    for (int shift = 8; shift >= 0; shift -= 8) frame += static_cast<char>((n >> shift) & 0xff);
  } else {
    frame += static_cast<char>(0x80 | 127);
    for (int shift = 56; shift >= 0; shift -= 8) frame += static_cast<char>((n >> shift) & 0xff);
  }
  frame.append(4, '\0');
  return frame + payload;
}

class ViewerHostile : public ::testing::Test {
 protected:
  void start(const std::vector<std::string>& extra = {}) {
    std::vector<std::string> argv{UBERSIM_VIEWER_EXE, "--port", "0"};
    argv.insert(argv.end(), extra.begin(), extra.end());
    viewer_ = std::make_unique<ChildProcess>(argv, ::testing::TempDir() + "viewer_hostile.log");
    ASSERT_TRUE(viewer_->wait_for_output("viewer: http://", 10)) << viewer_->log();
    const std::string log = viewer_->log();
    const auto at = log.find("viewer: http://127.0.0.1:");
    ASSERT_NE(at, std::string::npos) << log;
    port_ = std::stoi(log.substr(at + 25));
    host_ = "127.0.0.1:" + std::to_string(port_);
    bus_.subscribe<ubersim::sim_control_t>("SIM_CONTROL", [this](const ubersim::sim_control_t& c) {
      if (c.action != ubersim::sim_control_t::REQUEST_GEOMETRY) controls_.push_back(c);
    });
  }
  // Waits for `count` control requests from the viewer on SIM_CONTROL.
  bool wait_for_controls(size_t count, double timeout_s = 5) {
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (controls_.size() < count && std::chrono::steady_clock::now() < deadline) {
      bus_.wait_and_handle(20);
    }
    return controls_.size() >= count;
  }
  std::string stop_within_a_second() {
    const auto start_time = std::chrono::steady_clock::now();
    EXPECT_EQ(viewer_->stop(5, SIGINT), 0) << viewer_->log();
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count(),
              1.0);
    std::string log = viewer_->log();
    viewer_.reset();
    return log;
  }

  ubersim::MessageBus bus_{ubersim::default_lcm_url()};
  std::unique_ptr<ChildProcess> viewer_;
  int port_ = 0;
  std::string host_;
  std::vector<ubersim::sim_control_t> controls_;
};

}  // namespace

TEST_F(ViewerHostile, OtherSitesPagesAreRefusedUnlessAllowed) {
  start();
  const auto head = [this](const std::string& host, const std::string& origin) {
    Socket socket(port_);
    EXPECT_TRUE(socket.send(handshake(host, origin)));
    return socket.response_head();
  };
  EXPECT_TRUE(opened(head(host_, "http://" + host_))) << "the viewer's own page";
  EXPECT_TRUE(opened(head(host_, ""))) << "no Origin: not a browser";
  EXPECT_TRUE(opened(
      head("localhost:" + std::to_string(port_), "http://localhost:" + std::to_string(port_))));
  const std::string other = head(host_, "http://evil.example");
  EXPECT_EQ(other.rfind("HTTP/1.1 403", 0), 0u) << other;
  // DNS rebinding: the other site's own name, pointed at 127.0.0.1.
  const std::string rebound = "evil.example:" + std::to_string(port_);
  EXPECT_EQ(head(rebound, "http://" + rebound).rfind("HTTP/1.1 403", 0), 0u);
  // A refused page's requests never reach physics.
  {
    Socket socket(port_);
    socket.send(handshake(host_, "http://evil.example") + text_frame(R"({"action":"pause"})"));
    socket.until_closed();
  }
  EXPECT_FALSE(wait_for_controls(1, 0.5));
  const std::string log = stop_within_a_second();
  EXPECT_NE(log.find("--allow-origin"), std::string::npos) << "the refusal says how to allow it";

  controls_.clear();
  start({"--allow-origin", "http://evil.example"});
  Socket allowed(port_);
  allowed.send(handshake(host_, "http://evil.example"));
  ASSERT_TRUE(opened(allowed.response_head()));
  allowed.send(text_frame(R"({"action":"pause"})"));
  ASSERT_TRUE(wait_for_controls(1));
  EXPECT_EQ(controls_[0].action, +ubersim::sim_control_t::PAUSE);
  stop_within_a_second();
}

TEST_F(ViewerHostile, FramesAtTheLimitPassAboveItCloseTheConnection) {
  start();
  const long rss_before = resident_kilobytes(viewer_->pid());
  // Exactly 64 KB: a request padded with spaces still goes through.
  std::string at_limit = R"({"action":"resume"})";
  at_limit.append(64 * 1024 - at_limit.size(), ' ');
  Socket page(port_);
  page.send(handshake(host_, "http://" + host_));
  ASSERT_TRUE(opened(page.response_head()));
  ASSERT_TRUE(page.send(text_frame(at_limit)));
  ASSERT_TRUE(wait_for_controls(1));
  EXPECT_EQ(controls_[0].action, +ubersim::sim_control_t::RESUME);
  // One byte more: the connection is closed (1009, message too big), nothing published.
  ASSERT_TRUE(page.send(text_frame(at_limit + " ")));
  const std::string closing = page.until_closed();
  ASSERT_GE(closing.size(), 4u);
  const size_t at = closing.size() - 4;  // close frame: 0x88, length 2+, code
  EXPECT_NE(closing.find(std::string("\x03\xf1", 2)), std::string::npos)
      << "close code 1009 expected; got " << closing.size() << " bytes from " << at;
  // A frame claiming 4 GB is refused before any of it is buffered.
  {
    Socket huge(port_);
    huge.send(handshake(host_, ""));
    ASSERT_TRUE(opened(huge.response_head()));
    std::string header = "\x81\xff";
    for (int i = 0; i < 8; ++i) header += i == 3 ? '\x01' : '\0';  // 2^32 bytes
    header.append(4, '\0');
    huge.send(header + std::string(1000, 'x'));
    huge.until_closed();
  }
  // JSON nesting bombs: refused unparsed; the page stays connected and usable.
  Socket bomber(port_);
  bomber.send(handshake(host_, ""));
  ASSERT_TRUE(opened(bomber.response_head()));
  for (int i = 0; i < 50; ++i) {
    ASSERT_TRUE(bomber.send(text_frame(std::string(60000, i % 2 ? '[' : '{'))));
  }
  std::string deep_but_valid = R"({"action":"pause","x":)";
  for (int i = 0; i < 5000; ++i) deep_but_valid += "[";
  for (int i = 0; i < 5000; ++i) deep_but_valid += "]";
  ASSERT_TRUE(bomber.send(text_frame(deep_but_valid + "}")));
  ASSERT_TRUE(bomber.send(text_frame(R"({"action":"speed","factor":2})")));
  ASSERT_TRUE(wait_for_controls(2));
  EXPECT_EQ(controls_.size(), 2u) << "only the flat requests";
  EXPECT_EQ(controls_[1].action, +ubersim::sim_control_t::SET_SPEED);
  const long rss_after = resident_kilobytes(viewer_->pid());
  std::printf("viewer resident memory: %ld kB before, %ld kB after ~6 MB of hostile frames\n",
              rss_before, rss_after);
  EXPECT_LT(rss_after - rss_before, 30 * 1024);
  const std::string log = stop_within_a_second();
  EXPECT_NE(log.find("nested deeper than"), std::string::npos) << log;
}

TEST_F(ViewerHostile, TwoHundredConnectionsOpenSixteenPages) {
  start();
  const long rss_before = resident_kilobytes(viewer_->pid());
  std::vector<std::unique_ptr<Socket>> sockets;
  int pages = 0, busy = 0;
  for (int i = 0; i < 200; ++i) {
    sockets.push_back(std::make_unique<Socket>(port_));
    ASSERT_TRUE(sockets.back()->connected());
    sockets.back()->send(handshake(host_, "http://" + host_));
    const std::string head = sockets.back()->response_head();
    if (opened(head)) ++pages;
    if (head.rfind("HTTP/1.1 503", 0) == 0) ++busy;
  }
  const long rss_full = resident_kilobytes(viewer_->pid());
  std::printf("200 connections: %d pages, %d refused busy; memory %ld kB -> %ld kB\n", pages, busy,
              rss_before, rss_full);
  EXPECT_EQ(pages, 16);
  EXPECT_EQ(busy, 184);
  EXPECT_LT(rss_full - rss_before, 30 * 1024);
  // The pages go: new ones open again.
  sockets.clear();
  bool reopened = false;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (!reopened && std::chrono::steady_clock::now() < deadline) {
    Socket socket(port_);
    socket.send(handshake(host_, ""));
    reopened = opened(socket.response_head());
  }
  EXPECT_TRUE(reopened);
  stop_within_a_second();
}
