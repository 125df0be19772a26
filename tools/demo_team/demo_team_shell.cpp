#include "demo_team_shell.hpp"

#include <chrono>
#include <optional>
#include <string>

#include "ubersim/process_host.hpp"
#include "ubersim/spdlog.hpp"
#include "ubersim/sync_client.hpp"
#include "ubersim/topics.hpp"

namespace demo {
namespace {

namespace topics = ubersim::topics;
using ubersim::ProcessHost;

// The demo team's shell: its core fed from VISION, VISION_GEOMETRY and
// REFEREE; with --sync a sync client that registers, renews and says goodbye.
class DemoTeamShell {
 public:
  DemoTeamShell(const DemoTeamOptions& options, ubersim::Team own, ProcessHost& host)
      : options_(options),
        own_(own),
        host_(host),
        team_(options, own, host.bus(), host.channels()) {}
  DemoTeamShell(const DemoTeamShell&) = delete;
  DemoTeamShell& operator=(const DemoTeamShell&) = delete;

  int run() {
    subscribe();
    // Sync mode's registration: said now, again every second (for a radio
    // emulator that starts later), goodbye at the stop.
    if (options_.sync) {
      sync_client_.emplace(host_.bus(), host_.channels(), own_, host_.name());
      sync_client_->join(host_.now());
      host_.after_wake([this](ProcessHost::Clock::time_point now) { sync_client_->tick(now); });
      host_.at_stop([this] { sync_client_->leave(); });
    }
    host_.at_stop([this] { spdlog::info("stopped after {} packets", team_.packets()); });
    return host_.run(std::chrono::milliseconds(100));
  }

 private:
  void subscribe() {
    ubersim::subscribe(host_.bus(), host_.channels(), topics::kVisionGeometry,
                       [this](const ubersim::vision_geometry_t& g) { team_.on_geometry(g); });
    ubersim::subscribe(host_.bus(), host_.channels(), topics::kReferee,
                       [this](const ubersim::referee_t& r) { team_.on_referee(r); });
    ubersim::subscribe(host_.bus(), host_.channels(), topics::kVision,
                       [this](const ubersim::vision_frame_t& frame) { team_.on_frame(frame); });
    spdlog::info("{} team, mode {}, defending the {} goal: listening on {}, sending on {}",
                 ubersim::team_name(own_), options_.mode,
                 team_.setup().defends < 0 ? "negative-x" : "positive-x",
                 ubersim::channel_name(host_.channels(), topics::kVision),
                 ubersim::channel_name(host_.channels(), topics::kRadio.of(own_)));
  }

  const DemoTeamOptions& options_;
  ubersim::Team own_;
  ProcessHost& host_;
  DemoTeam team_;
  std::optional<ubersim::SyncClient> sync_client_;
};

}  // namespace

int run_demo_team(const DemoTeamOptions& options, ubersim::Team own) {
  ProcessHost host(options.common, std::string("demo_") + ubersim::team_name(own));
  DemoTeamShell shell(options, own, host);
  return shell.run();
}

}  // namespace demo
