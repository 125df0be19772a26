#include "ubersim/viewer/web_server.hpp"

#include <spdlog/spdlog.h>

#include <fstream>
#include <mutex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <websocketpp/config/asio_no_tls.hpp>
#include <websocketpp/server.hpp>

namespace ubersim::viewer {
namespace {
using Server = websocketpp::server<websocketpp::config::asio>;
using Handle = websocketpp::connection_hdl;

bool ends_with(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() &&
         text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}
}  // namespace

std::string content_type_for(const std::string& file_name) {
  if (ends_with(file_name, ".html")) return "text/html; charset=utf-8";
  if (ends_with(file_name, ".js")) return "text/javascript; charset=utf-8";
  if (ends_with(file_name, ".css")) return "text/css; charset=utf-8";
  if (ends_with(file_name, ".png")) return "image/png";
  if (ends_with(file_name, ".svg")) return "image/svg+xml";
  return "application/octet-stream";
}

std::string served_file_name(const std::string& request_path) {
  std::string path = request_path.substr(0, request_path.find_first_of("?#"));
  if (path.empty() || path[0] != '/') return "";
  path.erase(0, 1);
  if (path.empty()) return "index.html";
  // Plain file names only: nothing outside the web folder can be named.
  if (path[0] == '.') return "";
  for (char c : path) {
    const bool allowed = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                         (c >= '0' && c <= '9') || c == '_' || c == '-' || c == '.';
    if (!allowed) return "";
  }
  return path;
}

struct WebServer::Impl {
  WebServerOptions options;
  MessageHandler on_message;
  Server server;
  std::thread thread;
  std::set<Handle, std::owner_less<Handle>> connections;  // server thread only

  std::mutex pending_mutex;
  std::shared_ptr<const std::string> pending;  // newest frame not yet flushed
  bool flush_scheduled = false;

  std::atomic<std::uint64_t> clients{0};
  std::atomic<std::uint64_t> sent{0};
  std::atomic<std::uint64_t> bytes{0};
  std::atomic<std::uint64_t> skipped{0};
  std::atomic<std::uint64_t> replaced{0};

  void serve_http(const Handle& handle) {
    Server::connection_ptr connection = server.get_con_from_hdl(handle);
    const std::string name = served_file_name(connection->get_resource());
    std::ifstream file;
    if (!name.empty()) file.open(options.web_dir + "/" + name, std::ios::binary);
    if (name.empty() || !file.is_open()) {
      connection->set_status(websocketpp::http::status_code::not_found);
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
  }

  void flush() {
    std::shared_ptr<const std::string> frame;
    {
      std::lock_guard<std::mutex> lock(pending_mutex);
      frame = std::move(pending);
      pending.reset();
      flush_scheduled = false;
    }
    if (!frame) return;
    for (const Handle& handle : connections) {
      websocketpp::lib::error_code error;
      Server::connection_ptr connection = server.get_con_from_hdl(handle, error);
      if (error || connection->get_state() != websocketpp::session::state::open) continue;
      if (connection->get_buffered_amount() > options.max_buffered_bytes) {
        ++skipped;
        continue;
      }
      error = connection->send(*frame, websocketpp::frame::opcode::text);
      if (error) {
        ++skipped;
      } else {
        ++sent;
        bytes += frame->size();
      }
    }
  }
};

WebServer::WebServer(const WebServerOptions& options, MessageHandler on_message)
    : impl_(std::make_unique<Impl>()) {
  Impl& impl = *impl_;
  impl.options = options;
  impl.on_message = std::move(on_message);
  Server& server = impl.server;
  server.clear_access_channels(websocketpp::log::alevel::all);
  server.clear_error_channels(websocketpp::log::elevel::all);
  server.init_asio();
  server.set_reuse_addr(true);
  server.set_max_message_size(std::size_t{64} * 1024);  // control requests are tiny
  server.set_http_handler([&impl](const Handle& handle) { impl.serve_http(handle); });
  server.set_open_handler([&impl](const Handle& handle) {
    impl.connections.insert(handle);
    impl.clients = impl.connections.size();
  });
  server.set_close_handler([&impl](const Handle& handle) {
    impl.connections.erase(handle);
    impl.clients = impl.connections.size();
  });
  server.set_fail_handler([&impl](const Handle& handle) { impl.connections.erase(handle); });
  server.set_message_handler([&impl](const Handle&, const Server::message_ptr& message) {
    if (message->get_opcode() == websocketpp::frame::opcode::text) {
      impl.on_message(message->get_payload());
    }
  });

  websocketpp::lib::error_code error;
  const auto address = asio::ip::make_address(options.bind_address, error);
  if (error) throw std::runtime_error("--bind: not an IP address: " + options.bind_address);
  server.listen(asio::ip::tcp::endpoint(address, options.port), error);
  if (error) {
    throw std::runtime_error("cannot listen on " + options.bind_address + ":" +
                             std::to_string(options.port) + ": " + error.message());
  }
  server.start_accept(error);
  if (error) throw std::runtime_error("cannot accept connections: " + error.message());
  impl.thread = std::thread([&impl] {
    try {
      impl.server.run();
    } catch (const std::exception& exception) {
      spdlog::error("web server stopped: {}", exception.what());
    }
  });
}

WebServer::~WebServer() {
  Impl& impl = *impl_;
  asio::post(impl.server.get_io_service(), [&impl] {
    websocketpp::lib::error_code error;
    impl.server.stop_listening(error);
    for (const Handle& handle : impl.connections) {
      impl.server.close(handle, websocketpp::close::status::going_away, "viewer stopping", error);
    }
  });
  // Give pages a moment to receive the close, then stop whatever is left.
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  impl.server.stop();
  if (impl.thread.joinable()) impl.thread.join();
}

std::uint16_t WebServer::port() const {
  websocketpp::lib::error_code error;
  const auto endpoint = impl_->server.get_local_endpoint(error);
  return error ? 0 : endpoint.port();
}

void WebServer::publish(std::shared_ptr<const std::string> frame) {
  Impl& impl = *impl_;
  std::lock_guard<std::mutex> lock(impl.pending_mutex);
  if (impl.pending) ++impl.replaced;
  impl.pending = std::move(frame);
  if (impl.flush_scheduled) return;
  impl.flush_scheduled = true;
  asio::post(impl.server.get_io_service(), [&impl] { impl.flush(); });
}

WebServerStats WebServer::stats() const {
  WebServerStats stats;
  stats.clients = impl_->clients.load();
  stats.frames_sent = impl_->sent.load();
  stats.bytes_sent = impl_->bytes.load();
  stats.frames_skipped = impl_->skipped.load();
  stats.frames_replaced = impl_->replaced.load();
  return stats;
}

}  // namespace ubersim::viewer
