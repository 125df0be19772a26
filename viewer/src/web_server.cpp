#include "ubersim/viewer/web_server.hpp"

#include <mutex>
#include <stdexcept>
#include <thread>
#include <websocketpp/config/asio_no_tls.hpp>
#include <websocketpp/server.hpp>

#include "ubersim/spdlog.hpp"
#include "ubersim/viewer/server_handlers.hpp"

namespace ubersim::viewer {
namespace {
using Server = websocketpp::server<websocketpp::config::asio>;
using Handle = websocketpp::connection_hdl;
}  // namespace

struct WebServer::Impl {
  WebServerOptions options;
  MessageHandler on_message;
  Server server;
  std::thread thread;
  RequestLimits limits;
  Pages pages;

  std::mutex pending_mutex;
  std::shared_ptr<const std::string> pending;  // newest frame not yet flushed
  bool flush_scheduled = false;

  std::atomic<std::uint64_t> sent{0};
  std::atomic<std::uint64_t> bytes{0};
  std::atomic<std::uint64_t> skipped{0};
  std::atomic<std::uint64_t> replaced{0};

  void flush() {
    std::shared_ptr<const std::string> frame;
    {
      std::lock_guard<std::mutex> lock(pending_mutex);
      frame = std::move(pending);
      pending.reset();
      flush_scheduled = false;
    }
    if (!frame) return;
    for (const Handle& handle : pages.open) {
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
  // A page that never finishes its handshake holds a socket and its buffers: not for long.
  server.set_open_handshake_timeout(2000);

  websocketpp::lib::error_code error;
  const auto address = asio::ip::make_address(options.bind_address, error);
  if (error) throw std::runtime_error("--bind: not an IP address: " + options.bind_address);
  impl.limits.web_dir = options.web_dir;
  impl.limits.max_pages = options.max_pages;
  impl.limits.allowed_origins = options.allowed_origins;
  impl.limits.loopback_bound = address.is_loopback();
  install_request_handling(server, impl.limits, impl.pages, impl.on_message);
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
    for (const Handle& handle : impl.pages.open) {
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
  stats.clients = impl_->pages.clients.load();
  stats.pages_refused = impl_->pages.refused.load();
  stats.frames_sent = impl_->sent.load();
  stats.bytes_sent = impl_->bytes.load();
  stats.frames_skipped = impl_->skipped.load();
  stats.frames_replaced = impl_->replaced.load();
  return stats;
}

}  // namespace ubersim::viewer
