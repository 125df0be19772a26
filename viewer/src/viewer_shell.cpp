#include "viewer_shell.hpp"

#include <chrono>
#include <cstdio>
#include <deque>
#include <memory>
#include <mutex>
#include <ubersim/field_geometry_t.hpp>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/referee_t.hpp>
#include <ubersim/sim_control_ack_t.hpp>
#include <ubersim/sim_control_t.hpp>
#include <ubersim/sim_state_t.hpp>
#include <ubersim/vision_frame_t.hpp>
#include <ubersim/vision_geometry_t.hpp>
#include <utility>

#include "ubersim/logging.hpp"
#include "ubersim/process_host.hpp"
#include "ubersim/sim_control_requests.hpp"
#include "ubersim/spdlog.hpp"
#include "ubersim/topics.hpp"
#include "ubersim/viewer/json_encoding.hpp"
#include "ubersim/viewer/viewer_model.hpp"

namespace ubersim::viewer {
namespace {

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

using Clock = ViewerModel::Clock;

// The viewer's shell: the model (what the page shows) and the web server on
// the host; the pages' requests go out on SIM_CONTROL from the host's thread.
class ViewerShell {
 public:
  ViewerShell(const ViewerOptions& options, ProcessHost& host);
  ViewerShell(const ViewerShell&) = delete;
  ViewerShell& operator=(const ViewerShell&) = delete;

  int run();

 private:
  void subscribe_model();
  void forward_page_requests();
  void send_frame(Clock::time_point now);
  void log_summary() const;

  const ViewerOptions& options_;
  ProcessHost& host_;
  ViewerModel model_;
  ControlInbox inbox_;
  ThrottledLog inbox_full_;
  ThrottledLog bad_request_;
  WebServer server_;
  Publisher<sim_control_t> control_;
  std::int64_t next_request_id_ = 1;
};

WebServerOptions server_options_of(const ViewerOptions& options) {
  WebServerOptions server_options;
  server_options.bind_address = options.bind;
  server_options.port = static_cast<std::uint16_t>(options.port);
  server_options.web_dir = options.web_dir;
  server_options.allowed_origins = options.allowed_origins;
  server_options.max_pages = static_cast<std::size_t>(options.max_pages);
  return server_options;
}

ViewerShell::ViewerShell(const ViewerOptions& options, ProcessHost& host)
    : options_(options),
      host_(host),
      server_(server_options_of(options),
              [this](const std::string& text) {
                if (!inbox_.push(text)) {
                  inbox_full_.warn("inbox", "page requests arrive faster than handled");
                }
              }),
      control_(host.bus(), host.channels(), topics::kSimControl) {
  subscribe_model();
}

int ViewerShell::run() {
  std::printf("viewer: http://%s:%u/\n", options_.bind.c_str(), server_.port());
  std::fflush(stdout);
  spdlog::info("serving {} at http://{}:{}/ ; {} frames/s; LCM {}", options_.web_dir, options_.bind,
               server_.port(), options_.display_rate, options_.common.lcm_url);

  // Ask physics for the field at once rather than wait for its next periodic one.
  control_(geometry_request("viewer", next_request_id_++));
  host_.after_wake([this](Clock::time_point) { forward_page_requests(); });
  // Ground truth at the display rate is all a page can show (physics
  // publishes no more for the viewer's sake).
  host_.ask_for_truth(periodic_demand(options_.display_rate));
  const auto frame_period = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(1.0 / options_.display_rate));
  host_
      .every(
          frame_period, [this](Clock::time_point now) { send_frame(now); },
          ProcessHost::Timer::Rate::FixedRate)
      .due_at(host_.now());
  host_.at_stop([this] { log_summary(); });
  return host_.run(std::chrono::seconds(1));
}

// Everything the page shows comes in here, into the model, stamped with the
// host's wall clock.
void ViewerShell::subscribe_model() {
  const ChannelNames& channels = host_.channels();
  MessageBus& bus = host_.bus();
  model_.set_channel_names({{"SIM_STATE", channel_name(channels, topics::kSimState)},
                            {"VISION", channel_name(channels, topics::kVision)},
                            {"VISION_GEOMETRY", channel_name(channels, topics::kVisionGeometry)},
                            {"SIM_GEOMETRY", channel_name(channels, topics::kSimGeometry)},
                            {"RADIO_YELLOW", channel_name(channels, topics::kRadio.yellow)},
                            {"RADIO_BLUE", channel_name(channels, topics::kRadio.blue)},
                            {"REFEREE", channel_name(channels, topics::kReferee)}});

  subscribe(bus, channels, topics::kSimState,
            [this](const sim_state_t& m) { model_.on_sim_state(m, host_.now()); });
  subscribe(bus, channels, topics::kVision,
            [this](const vision_frame_t& m) { model_.on_vision(m, host_.now()); });
  subscribe(bus, channels, topics::kVisionGeometry,
            [this](const vision_geometry_t& m) { model_.on_vision_geometry(m, host_.now()); });
  subscribe(bus, channels, topics::kSimGeometry,
            [this](const field_geometry_t& m) { model_.on_sim_geometry(m, host_.now()); });
  for (Team team : kTeams) {
    subscribe(bus, channels, topics::kRadio.of(team), [this, team](const radio_packet_t& m) {
      model_.on_radio(static_cast<int>(team), m, host_.now());
    });
  }
  subscribe(bus, channels, topics::kReferee,
            [this](const referee_t& m) { model_.on_referee(m, host_.now()); });
  subscribe(bus, channels, topics::kSimControlAck, [this](const sim_control_ack_t& ack) {
    if (ack.sender == "viewer") model_.on_ack(ack);
  });
}

// The pages' requests, checked, out on SIM_CONTROL (on the main thread: LCM's).
void ViewerShell::forward_page_requests() {
  for (const std::string& text : inbox_.take()) {
    auto parsed = parse_control_request(text, next_request_id_, "viewer");
    if (!parsed.request) {
      bad_request_.warn("request", "ignored a page request: " + parsed.error);
      continue;
    }
    ++next_request_id_;
    spdlog::debug("page request: {}", text);
    control_(*parsed.request);
  }
}

// One display frame to every open page (none is made while no page is open).
void ViewerShell::send_frame(Clock::time_point now) {
  const auto stats = server_.stats();
  if (stats.clients == 0) return;
  const nlohmann::json server_info = {{"clients", stats.clients},
                                      {"pages_refused", stats.pages_refused},
                                      {"display_rate", options_.display_rate},
                                      {"frames_skipped", stats.frames_skipped},
                                      {"malformed", host_.bus().malformed_count()}};
  server_.publish(std::make_shared<const std::string>(model_.snapshot(now, server_info)));
}

void ViewerShell::log_summary() const {
  const auto stats = server_.stats();
  spdlog::info(
      "frames sent {} (mean {} bytes), skipped for slow pages {}, replaced before sending {}; "
      "pages refused {}; page requests ignored {}; malformed LCM messages dropped {}",
      stats.frames_sent, stats.frames_sent > 0 ? stats.bytes_sent / stats.frames_sent : 0,
      stats.frames_skipped, stats.frames_replaced, stats.pages_refused,
      bad_request_.total() + inbox_full_.total(), host_.bus().malformed_count());
}

}  // namespace

int run_viewer(const ViewerOptions& options) {
  ProcessHost host(options.common, "viewer");
  ViewerShell shell(options, host);
  return shell.run();
}

}  // namespace ubersim::viewer
