// Fuzz target: the viewer's HTTP and WebSocket request handling. Each input is
// the byte stream a client sends on one TCP connection (an HTTP request, and
// after a WebSocket upgrade, frames). It runs through websocketpp's own HTTP
// parser, handshake and frame decoder with the viewer's handlers
// (install_request_handling: origin and page limits, static files, messages ->
// parse_control_request), on websocketpp's in-memory transport instead of a
// socket.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <websocketpp/config/core.hpp>
#include <websocketpp/server.hpp>

#include "fuzz_support.hpp"
#include "ubersim/viewer/json_encoding.hpp"
#include "ubersim/viewer/server_handlers.hpp"

namespace {

using Server = websocketpp::server<websocketpp::config::core>;

struct Endpoint {
  Server server;
  ubersim::viewer::RequestLimits limits;
  ubersim::viewer::Pages pages;
  std::ostringstream written;  // what the server answers; dropped after each input
  std::size_t requests = 0;

  Endpoint() {
    server.clear_access_channels(websocketpp::log::alevel::all);
    server.clear_error_channels(websocketpp::log::elevel::all);
    server.register_ostream(&written);
    limits.web_dir = UBERSIM_FUZZ_WEB_DIR;
    limits.max_pages = 2;  // low, so the refusal path is reached too
    ubersim::viewer::install_request_handling(
        server, limits, pages, [this](const std::string& text) {
          ++requests;
          (void)ubersim::viewer::parse_control_request(text, 1, "viewer");
        });
  }
};

Endpoint& endpoint() {
  static Endpoint instance;
  return instance;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  ubersim::fuzz::quiet_logging();
  endpoint();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Endpoint& e = endpoint();
  Server::connection_ptr connection = e.server.get_connection();
  connection->start();
  connection->read_all(reinterpret_cast<const char*>(data), size);
  connection->eof();  // the client went away: the page (if one opened) closes
  // One connection per input: the pages it opened are gone again.
  if (e.pages.open.size() > e.limits.max_pages) __builtin_trap();
  e.written.str("");
  return 0;
}
