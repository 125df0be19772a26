// ubersim_viewer: the live field viewer. Subscribes to ground truth, vision,
// field geometry, both teams' radio commands and the referee, and serves a web page that
// draws them, pushing it one snapshot per display frame over a WebSocket. The
// page's controls (pause, speed, reset, drag to place) go out on SIM_CONTROL.
// See docs/viewer.md.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <deque>
#include <mutex>
#include <ubersim/field_geometry_t.hpp>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/referee_t.hpp>
#include <ubersim/sim_control_ack_t.hpp>
#include <ubersim/sim_control_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <ubersim/vision_frame_t.hpp>
#include <ubersim/vision_geometry_t.hpp>

#include "ubersim/cli.hpp"
#include "ubersim/logging.hpp"
#include "ubersim/process_host.hpp"
#include "ubersim/process_main.hpp"
#include "ubersim/sim_control_requests.hpp"
#include "ubersim/topics.hpp"
#include "ubersim/viewer/json_encoding.hpp"
#include "ubersim/viewer/viewer_model.hpp"
#include "ubersim/viewer/web_server.hpp"

#ifndef UBERSIM_VIEWER_WEB_DIR
#error "UBERSIM_VIEWER_WEB_DIR must name the page's folder"
#endif

namespace {

struct Options {
  ubersim::CommonOptions common;
  std::string bind = "127.0.0.1";
  int port = 8080;
  double display_rate = 60;
  std::string web_dir = UBERSIM_VIEWER_WEB_DIR;
  std::vector<std::string> allowed_origins;
  int max_pages = static_cast<int>(ubersim::viewer::kDefaultMaxPages);
};

// Requests from pages arrive on the server's thread; LCM is used by the main
// thread only, so they wait here. Bounded: a page cannot flood physics.
class ControlInbox {
 public:
  static constexpr std::size_t kCapacity = 64;
  bool push(std::string text) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (queue_.size() >= kCapacity) return false;
    queue_.push_back(std::move(text));
    return true;
  }
  std::deque<std::string> take() {
    std::lock_guard<std::mutex> lock(mutex_);
    return std::exchange(queue_, {});
  }

 private:
  std::mutex mutex_;
  std::deque<std::string> queue_;
};

using Clock = ubersim::viewer::ViewerModel::Clock;

// Everything the page shows comes in here, into the model, stamped with the
// host's wall clock.
void subscribe_model(ubersim::ProcessHost& host, ubersim::viewer::ViewerModel& model) {
  using namespace ubersim;
  const ChannelNames& channels = host.channels();
  MessageBus& bus = host.bus();
  model.set_channel_names({{"SIM_STATE", channel_name(channels, topics::kSimState)},
                           {"VISION", channel_name(channels, topics::kVision)},
                           {"VISION_GEOMETRY", channel_name(channels, topics::kVisionGeometry)},
                           {"SIM_GEOMETRY", channel_name(channels, topics::kSimGeometry)},
                           {"RADIO_YELLOW", channel_name(channels, topics::kRadio.yellow)},
                           {"RADIO_BLUE", channel_name(channels, topics::kRadio.blue)},
                           {"REFEREE", channel_name(channels, topics::kReferee)}});

  subscribe(bus, channels, topics::kSimState,
            [&](const sim_state_t& m) { model.on_sim_state(m, host.now()); });
  subscribe(bus, channels, topics::kVision,
            [&](const vision_frame_t& m) { model.on_vision(m, host.now()); });
  subscribe(bus, channels, topics::kVisionGeometry,
            [&](const vision_geometry_t& m) { model.on_vision_geometry(m, host.now()); });
  subscribe(bus, channels, topics::kSimGeometry,
            [&](const field_geometry_t& m) { model.on_sim_geometry(m, host.now()); });
  for (Team team : kTeams) {
    subscribe(bus, channels, topics::kRadio.of(team), [&, team](const radio_packet_t& m) {
      model.on_radio(static_cast<int>(team), m, host.now());
    });
  }
  subscribe(bus, channels, topics::kReferee,
            [&](const referee_t& m) { model.on_referee(m, host.now()); });
  subscribe(bus, channels, topics::kSimControlAck, [&](const sim_control_ack_t& ack) {
    if (ack.sender == "viewer") model.on_ack(ack);
  });
}

ubersim::viewer::WebServerOptions server_options_of(const Options& options) {
  ubersim::viewer::WebServerOptions server_options;
  server_options.bind_address = options.bind;
  server_options.port = static_cast<std::uint16_t>(options.port);
  server_options.web_dir = options.web_dir;
  server_options.allowed_origins = options.allowed_origins;
  server_options.max_pages = static_cast<std::size_t>(options.max_pages);
  return server_options;
}

// The pages' requests, checked, out on SIM_CONTROL (on the main thread: LCM's).
void forward_page_requests(ControlInbox& inbox,
                           const ubersim::Publisher<ubersim::sim_control_t>& control,
                           std::int64_t& next_request_id, ubersim::ThrottledLog& bad_request) {
  for (const std::string& text : inbox.take()) {
    auto parsed = ubersim::viewer::parse_control_request(text, next_request_id, "viewer");
    if (!parsed.request) {
      bad_request.warn("request", "ignored a page request: " + parsed.error);
      continue;
    }
    ++next_request_id;
    spdlog::debug("page request: {}", text);
    control(*parsed.request);
  }
}

// One display frame to every open page (none is made while no page is open).
void send_frame(ubersim::viewer::WebServer& server, ubersim::viewer::ViewerModel& model,
                double display_rate, std::uint64_t malformed, Clock::time_point now) {
  const auto stats = server.stats();
  if (stats.clients == 0) return;
  const nlohmann::json server_info = {{"clients", stats.clients},
                                      {"pages_refused", stats.pages_refused},
                                      {"display_rate", display_rate},
                                      {"frames_skipped", stats.frames_skipped},
                                      {"malformed", malformed}};
  server.publish(std::make_shared<const std::string>(model.snapshot(now, server_info)));
}

int run(const Options& options) {
  using namespace ubersim;
  ProcessHost host(options.common, "viewer");
  viewer::ViewerModel model;
  subscribe_model(host, model);

  ControlInbox inbox;
  ThrottledLog inbox_full;
  viewer::WebServer server(server_options_of(options), [&](const std::string& text) {
    if (!inbox.push(text)) inbox_full.warn("inbox", "page requests arrive faster than handled");
  });
  std::printf("viewer: http://%s:%u/\n", options.bind.c_str(), server.port());
  std::fflush(stdout);
  spdlog::info("serving {} at http://{}:{}/ ; {} frames/s; LCM {}", options.web_dir, options.bind,
               server.port(), options.display_rate, options.common.lcm_url);

  // Ask physics for the field at once rather than wait for its next periodic one.
  const Publisher<sim_control_t> control(host.bus(), host.channels(), topics::kSimControl);
  std::int64_t next_request_id = 1;
  control(geometry_request("viewer", next_request_id++));

  ThrottledLog bad_request;
  host.after_wake([&](Clock::time_point) {
    forward_page_requests(inbox, control, next_request_id, bad_request);
  });
  // Ground truth at the display rate is all a page can show (physics
  // publishes no more for the viewer's sake).
  host.ask_for_truth(periodic_demand(options.display_rate));
  const auto frame_period = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(1.0 / options.display_rate));
  host.every(
          frame_period,
          [&](Clock::time_point now) {
            send_frame(server, model, options.display_rate, host.bus().malformed_count(), now);
          },
          ProcessHost::Timer::Rate::FixedRate)
      .due_at(host.now());
  host.at_stop([&] {
    const auto stats = server.stats();
    spdlog::info(
        "frames sent {} (mean {} bytes), skipped for slow pages {}, replaced before sending {}; "
        "pages refused {}; page requests ignored {}; malformed LCM messages dropped {}",
        stats.frames_sent, stats.frames_sent > 0 ? stats.bytes_sent / stats.frames_sent : 0,
        stats.frames_skipped, stats.frames_replaced, stats.pages_refused,
        bad_request.total() + inbox_full.total(), host.bus().malformed_count());
  });
  return host.run(std::chrono::seconds(1));
}

int parse_and_run(int argc, char** argv) {
  Options options;
  CLI::App app{"ubersim viewer: the field, ground truth, vision and commands in a web browser"};
  ubersim::add_common_options(app, options.common);
  app.add_option("--port", options.port, "HTTP/WebSocket port (0 = any free port)")
      ->check(ubersim::in_range(0, 65535))
      ->capture_default_str();
  app.add_option("--bind", options.bind,
                 "address to listen on (0.0.0.0 lets other machines in: there is no password)")
      ->capture_default_str();
  app.add_option("--display-rate", options.display_rate,
                 "snapshots per second sent to each page (messages are coalesced to this)")
      ->check(ubersim::in_range(1.0, 240.0))
      ->capture_default_str();
  app.add_option("--web-dir", options.web_dir, "folder of the page's files")->capture_default_str();
  app.add_option(
      "--allow-origin", options.allowed_origins,
      "let pages of this other origin (e.g. http://example.org:8000, or * for any) open "
      "the WebSocket and send control requests; by default only the viewer's own page may");
  app.add_option("--max-pages", options.max_pages, "pages (WebSocket connections) open at once")
      ->check(ubersim::in_range(1, 1024))
      ->capture_default_str();
  if (const auto stop = ubersim::parse_command_line(app, argc, argv)) return *stop;

  ubersim::setup_logging("viewer", options.common.verbosity());
  return run(options);
}

}  // namespace

int main(int argc, char** argv) {
  return ubersim::run_main("ubersim_viewer", [&] { return parse_and_run(argc, argv); });
}
