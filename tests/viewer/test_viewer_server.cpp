// The viewer's HTTP/WebSocket server over real TCP on 127.0.0.1: it serves the
// page's files and nothing else, pushes published frames, hands page messages
// on, and a page that stops reading costs skipped frames, not memory.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <condition_variable>
#include <fstream>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "read_file.hpp"
#include "ubersim/viewer/web_server.hpp"

namespace ubersim::viewer {
namespace {

// A TCP connection to the server, closed on destruction.
class Socket {
 public:
  explicit Socket(std::uint16_t port, int receive_buffer = 0) {
    fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    if (receive_buffer > 0) {
      ::setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &receive_buffer, sizeof receive_buffer);
    }
    timeval timeout{5, 0};
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(port);
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    connected_ = ::connect(fd_, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0;
  }
  ~Socket() { ::close(fd_); }
  bool connected() const { return connected_; }
  void send(const std::string& bytes) {
    ASSERT_EQ(::send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL),
              static_cast<ssize_t>(bytes.size()));
  }
  // Reads until `enough` says so, the peer closes, or 5 s pass.
  std::string receive_until(const std::function<bool(const std::string&)>& enough) {
    std::string text;
    char buffer[65536];
    while (!enough(text)) {
      const ssize_t n = ::recv(fd_, buffer, sizeof buffer, 0);
      if (n <= 0) break;
      text.append(buffer, static_cast<std::size_t>(n));
    }
    return text;
  }

 private:
  int fd_ = -1;
  bool connected_ = false;
};

std::string http_get(std::uint16_t port, const std::string& path) {
  Socket socket(port);
  EXPECT_TRUE(socket.connected());
  socket.send("GET " + path + " HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n");
  return socket.receive_until([](const std::string&) { return false; });
}

using ubersim::test::read_file;

void websocket_handshake(Socket& socket) {
  socket.send(
      "GET / HTTP/1.1\r\nHost: 127.0.0.1\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
      "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n\r\n");
  const std::string reply = socket.receive_until(
      [](const std::string& t) { return t.find("\r\n\r\n") != std::string::npos; });
  ASSERT_EQ(reply.rfind("HTTP/1.1 101", 0), 0u) << reply;
}

// A masked client text frame (mask key 0: the payload stays readable).
std::string client_text_frame(const std::string& payload) {
  std::string frame{static_cast<char>(0x81), static_cast<char>(0x80 | payload.size())};
  frame.append(4, '\0');
  return frame + payload;
}

// Text payloads of the complete server frames at the start of `bytes`.
std::vector<std::string> server_frames(const std::string& bytes) {
  std::vector<std::string> payloads;
  std::size_t at = 0;
  while (at + 2 <= bytes.size()) {
    std::size_t length = static_cast<unsigned char>(bytes[at + 1]) & 0x7F;
    std::size_t header = 2;
    if (length == 126) {
      if (at + 4 > bytes.size()) break;
      length = (static_cast<unsigned char>(bytes[at + 2]) << 8) |
               static_cast<unsigned char>(bytes[at + 3]);
      header = 4;
    } else if (length == 127) {
      if (at + 10 > bytes.size()) break;
      length = 0;
      for (int i = 0; i < 8; ++i)
        length = (length << 8) | static_cast<unsigned char>(bytes[at + 2 + i]);
      header = 10;
    }
    if (at + header + length > bytes.size()) break;
    payloads.push_back(bytes.substr(at + header, length));
    at += header + length;
  }
  return payloads;
}

bool wait_for(const std::function<bool()>& done, double timeout_s = 5) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (!done() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return done();
}

long resident_kilobytes() {
  std::ifstream statm("/proc/self/statm");
  long pages_total = 0, pages_resident = 0;
  statm >> pages_total >> pages_resident;
  return pages_resident * (::sysconf(_SC_PAGESIZE) / 1024);
}

class ViewerServerTest : public ::testing::Test {
 protected:
  ViewerServerTest() {
    WebServerOptions options;
    options.port = 0;
    options.web_dir = UBERSIM_VIEWER_WEB_DIR;
    server_ = std::make_unique<WebServer>(options, [this](const std::string& text) {
      std::lock_guard<std::mutex> lock(mutex_);
      received_.push_back(text);
    });
  }
  std::unique_ptr<WebServer> server_;
  std::mutex mutex_;
  std::vector<std::string> received_;
};

TEST(ViewerServedFiles, OnlyPlainFileNamesInTheWebFolder) {
  EXPECT_EQ(served_file_name("/"), "index.html");
  EXPECT_EQ(served_file_name("/viewer.js"), "viewer.js");
  EXPECT_EQ(served_file_name("/viewer.js?v=2"), "viewer.js");
  EXPECT_EQ(served_file_name("/../CMakeLists.txt"), "");
  EXPECT_EQ(served_file_name("/..%2fsecret"), "");
  EXPECT_EQ(served_file_name("/a/b.js"), "");
  EXPECT_EQ(served_file_name("/.hidden"), "");
  EXPECT_EQ(served_file_name("relative"), "");
  EXPECT_EQ(content_type_for("index.html"), "text/html; charset=utf-8");
  EXPECT_EQ(content_type_for("viewer.js"), "text/javascript; charset=utf-8");
  EXPECT_EQ(content_type_for("viewer.css"), "text/css; charset=utf-8");
}

TEST_F(ViewerServerTest, ServesThePageFilesAndRefusesEverythingElse) {
  ASSERT_NE(server_->port(), 0);
  const std::string page = http_get(server_->port(), "/");
  EXPECT_EQ(page.rfind("HTTP/1.1 200", 0), 0u) << page.substr(0, 200);
  EXPECT_NE(page.find("Content-Type: text/html"), std::string::npos);
  const std::string index = read_file(std::string(UBERSIM_VIEWER_WEB_DIR) + "/index.html");
  ASSERT_FALSE(index.empty());
  EXPECT_EQ(page.substr(page.size() - index.size()), index) << "the file, byte for byte";
  const std::string script = http_get(server_->port(), "/viewer.js");
  EXPECT_EQ(script.rfind("HTTP/1.1 200", 0), 0u);
  EXPECT_NE(script.find("text/javascript"), std::string::npos);
  for (const char* path : {"/missing.html", "/../CMakeLists.txt", "/web/index.html"}) {
    EXPECT_EQ(http_get(server_->port(), path).rfind("HTTP/1.1 404", 0), 0u) << path;
  }
}

TEST_F(ViewerServerTest, PushesPublishedFramesAndHandsPageMessagesOn) {
  Socket page(server_->port());
  ASSERT_TRUE(page.connected());
  websocket_handshake(page);
  ASSERT_TRUE(wait_for([&] { return server_->stats().clients == 1; }));

  server_->publish(std::make_shared<const std::string>(R"({"type":"frame","n":1})"));
  const auto frames = server_frames(
      page.receive_until([](const std::string& t) { return !server_frames(t).empty(); }));
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0], R"({"type":"frame","n":1})");

  page.send(client_text_frame(R"({"action":"pause"})"));
  ASSERT_TRUE(wait_for([&] {
    std::lock_guard<std::mutex> lock(mutex_);
    return !received_.empty();
  }));
  std::lock_guard<std::mutex> lock(mutex_);
  EXPECT_EQ(received_.front(), R"({"action":"pause"})");
}

TEST_F(ViewerServerTest, PublishingFasterThanThePageReadsKeepsOnlyTheNewestFrame) {
  Socket page(server_->port());
  websocket_handshake(page);
  ASSERT_TRUE(wait_for([&] { return server_->stats().clients == 1; }));
  // A burst: most are replaced before the server thread gets to them.
  for (int i = 0; i < 1000; ++i) {
    server_->publish(std::make_shared<const std::string>("frame " + std::to_string(i)));
  }
  const auto frames = server_frames(page.receive_until([](const std::string& t) {
    const auto f = server_frames(t);
    return !f.empty() && f.back() == "frame 999";
  }));
  ASSERT_FALSE(frames.empty());
  EXPECT_EQ(frames.back(), "frame 999") << "the newest frame always arrives";
  const auto stats = server_->stats();
  EXPECT_EQ(stats.frames_sent, frames.size());
  EXPECT_EQ(stats.frames_sent + stats.frames_replaced, 1000u);
}

TEST_F(ViewerServerTest, APageThatStopsReadingCostsFramesNotMemory) {
  Socket stalled(server_->port(), /*receive_buffer=*/4096);
  websocket_handshake(stalled);
  ASSERT_TRUE(wait_for([&] { return server_->stats().clients == 1; }));
  const long rss_before = resident_kilobytes();
  // 400 frames of 200 kB (80 MB in all) to a page that never reads.
  const std::string big(200 * 1024, 'x');
  for (int i = 0; i < 400; ++i) {
    server_->publish(std::make_shared<const std::string>(big));
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ASSERT_TRUE(wait_for([&] {
    const auto s = server_->stats();
    return s.frames_sent + s.frames_skipped + s.frames_replaced == 400;
  }));
  const auto stats = server_->stats();
  const long growth_kb = resident_kilobytes() - rss_before;
  std::printf("stalled page: sent %llu, skipped %llu, replaced %llu; memory growth %ld kB\n",
              static_cast<unsigned long long>(stats.frames_sent),
              static_cast<unsigned long long>(stats.frames_skipped),
              static_cast<unsigned long long>(stats.frames_replaced), growth_kb);
  EXPECT_LT(stats.frames_sent, 40u) << "only what fits the socket and the 64 kB allowance";
  EXPECT_GT(stats.frames_skipped, 200u);
  EXPECT_LT(growth_kb, 20 * 1024) << "80 MB were offered; little may stay";
}

}  // namespace
}  // namespace ubersim::viewer
