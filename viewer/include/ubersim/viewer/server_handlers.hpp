#pragma once
// How the viewer's websocketpp endpoint treats each request: which handshakes
// open a page, which files HTTP serves, what a page's message turns into. A
// template over the endpoint's config so that WebServer (asio transport) and
// the fuzz target (websocketpp's in-memory iostream transport) run the same
// handlers on the same HTTP and WebSocket parser.
#include <atomic>
#include <cstdint>
#include <fstream>
#include <functional>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <websocketpp/server.hpp>

#include "ubersim/logging.hpp"
#include "ubersim/viewer/request_policy.hpp"

namespace ubersim::viewer {

struct RequestLimits {
  std::string web_dir;                       // the page's files
  std::size_t max_pages = kDefaultMaxPages;  // open WebSocket connections
  std::vector<std::string> allowed_origins;  // besides the page's own ("*": any)
  bool loopback_bound = true;                // listening on 127.0.0.1 / ::1 only
};

// The pages and what was refused. `open` is touched on the server's thread
// only; the counters are read by stats() from any thread.
struct Pages {
  std::set<websocketpp::connection_hdl, std::owner_less<websocketpp::connection_hdl>> open;
  std::atomic<std::uint64_t> clients{0};
  std::atomic<std::uint64_t> refused{0};           // handshakes refused (origin, too many pages)
  std::atomic<std::uint64_t> dropped_messages{0};  // binary messages from pages
  ThrottledLog log;
};

template <class Server>
void install_request_handling(Server& server, const RequestLimits& limits, Pages& pages,
                              std::function<void(const std::string&)> on_message) {
  using Handle = websocketpp::connection_hdl;
  using websocketpp::http::status_code::value;
  server.set_max_message_size(kMaxPageMessageBytes);
  server.set_max_http_body_size(kMaxHttpBodyBytes);

  server.set_validate_handler([&server, &limits, &pages](Handle handle) {
    auto connection = server.get_con_from_hdl(handle);
    const HandshakeDecision decision = decide_handshake(
        connection->get_request_header("Origin"), connection->get_request_header("Host"),
        limits.loopback_bound, limits.allowed_origins, pages.open.size(), limits.max_pages);
    if (decision.accept) return true;
    ++pages.refused;
    pages.log.warn("handshake_" + std::to_string(decision.status),
                   "refused a page: " + decision.reason);
    connection->set_status(static_cast<value>(decision.status));
    return false;
  });
  server.set_open_handler([&server, &limits, &pages](Handle handle) {
    // Handshakes validated together may all open: the bound holds here.
    if (pages.open.size() >= limits.max_pages) {
      ++pages.refused;
      websocketpp::lib::error_code error;
      server.close(handle, websocketpp::close::status::try_again_later, "too many pages", error);
      return;
    }
    pages.open.insert(handle);
    pages.clients = pages.open.size();
  });
  const auto forget = [&pages](Handle handle) {
    pages.open.erase(handle);
    pages.clients = pages.open.size();
  };
  server.set_close_handler(forget);
  server.set_fail_handler(forget);
  server.set_message_handler(
      [&pages, on_message = std::move(on_message)](Handle, typename Server::message_ptr message) {
        if (message->get_opcode() == websocketpp::frame::opcode::text) {
          on_message(message->get_payload());
        } else {
          ++pages.dropped_messages;
          pages.log.warn("binary", "dropped a binary message from a page (requests are JSON text)");
        }
      });
  server.set_http_handler([&server, &limits](Handle handle) {
    auto connection = server.get_con_from_hdl(handle);
    const std::string method = connection->get_request().get_method();
    const std::string name = served_file_name(connection->get_resource());
    std::ifstream file;
    if (!name.empty() && (method == "GET" || method == "HEAD")) {
      file.open(limits.web_dir + "/" + name, std::ios::binary);
    }
    if (!file.is_open()) {
      connection->set_status(name.empty() || method == "GET" || method == "HEAD"
                                 ? websocketpp::http::status_code::not_found
                                 : websocketpp::http::status_code::method_not_allowed);
      connection->set_body("not found\n");
      connection->append_header("Content-Type", "text/plain");
      return;
    }
    std::ostringstream body;
    body << file.rdbuf();
    connection->set_status(websocketpp::http::status_code::ok);
    connection->append_header("Content-Type", content_type_for(name));
    connection->append_header("Cache-Control", "no-store");
    connection->set_body(body.str());
  });
}

}  // namespace ubersim::viewer
