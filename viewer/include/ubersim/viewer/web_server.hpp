#pragma once
// The viewer's HTTP + WebSocket server (websocketpp on standalone asio, one
// thread of its own). It serves the page's static files from one folder and
// pushes frames to every connected page. publish() never blocks and never
// queues more than one frame: the newest replaces an unsent one, and a page
// whose socket already holds more than max_buffered_bytes unsent is skipped
// until it catches up, so a slow browser costs frames, not memory or time.
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "ubersim/viewer/request_policy.hpp"

namespace ubersim::viewer {

struct WebServerOptions {
  std::string bind_address = "127.0.0.1";
  std::uint16_t port = 8080;  // 0 = any free port (see WebServer::port())
  std::string web_dir;        // the page's files
  std::size_t max_buffered_bytes = std::size_t{64} * 1024;  // ~7 frames of 22 robots
  std::size_t max_pages = kDefaultMaxPages;                 // open pages at once
  std::vector<std::string> allowed_origins;                 // other sites' pages let in ("*": any)
};

struct WebServerStats {
  std::uint64_t clients = 0;
  std::uint64_t frames_sent = 0;      // frames handed to a socket, summed over pages
  std::uint64_t bytes_sent = 0;       // their payload bytes
  std::uint64_t frames_skipped = 0;   // frames a page was too far behind to take
  std::uint64_t frames_replaced = 0;  // frames replaced by a newer one before any send
  std::uint64_t pages_refused = 0;    // handshakes refused: other origin, too many pages
};

class WebServer {
 public:
  // Called on the server's thread with each text message a page sends.
  using MessageHandler = std::function<void(const std::string&)>;

  // Listens at once; throws std::runtime_error when it cannot (port taken ...).
  WebServer(const WebServerOptions& options, MessageHandler on_message);
  ~WebServer();  // closes every connection and joins the thread
  WebServer(const WebServer&) = delete;
  WebServer& operator=(const WebServer&) = delete;

  std::uint16_t port() const;  // the port actually bound
  // Thread-safe; the frame goes to every page soon after, unless a newer one replaces it.
  void publish(std::shared_ptr<const std::string> frame);
  WebServerStats stats() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ubersim::viewer
