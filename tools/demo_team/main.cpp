// ubersim_demo_team: a small control program written only against VISION and
// RADIO_<TEAM> — the interface a team's own software has on the real field.
// It acts on each vision frame (throttled to --rate in capture time, so it
// behaves the same at any simulation speed) and sends one radio packet.
// With --sync it is a sync client (docs/sync.md): it registers on SYNC_CLIENT
// and answers every frame, with an empty packet when it has nothing to send.
#include <CLI/CLI.hpp>
#include <chrono>
#include <iostream>
#include <optional>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/referee_t.hpp>
#include <ubersim/team_t.hpp>
#include <ubersim/vision_frame_t.hpp>
#include <ubersim/vision_geometry_t.hpp>

#include "behaviour.hpp"
#include "referee_rules.hpp"
#include "ubersim/cli.hpp"
#include "ubersim/field_side.hpp"
#include "ubersim/logging.hpp"
#include "ubersim/process_host.hpp"
#include "ubersim/process_main.hpp"
#include "ubersim/sync_client.hpp"
#include "ubersim/topics.hpp"

namespace {

struct Options {
  ubersim::CommonOptions common;
  std::string team_text = "yellow";
  std::string mode = "play";
  std::string defends_text;
  double rate = 60.0;
  double figure8_speed = 0.8;
  double figure8_size = 1.0;
  bool sync = false;
  demo::TeamSetup team;
};

// In play mode the referee decides what the team may do.
std::vector<ubersim::robot_command_t> play_by_the_rules(demo::GameMode mode,
                                                        const demo::WorldModel& world,
                                                        const demo::TeamSetup& team) {
  switch (mode) {
    case demo::GameMode::Halt:
    case demo::GameMode::Hold:
      return demo::halt(world);
    case demo::GameMode::Stop:
      return demo::keep_away(world, team);
    case demo::GameMode::Play:
      break;
  }
  return demo::play(world, team);
}

// The team itself: each vision frame updates what it sees, and at --rate (in
// capture time) it sends one radio packet. In sync mode it answers every
// frame: with an empty packet whose t_sent is the frame's t_capture when it
// has nothing to send (docs/sync.md).
class DemoTeam {
 public:
  DemoTeam(const Options& options, ubersim::Team own, ubersim::MessageBus& bus,
           const ubersim::ChannelNames& channels)
      : options_(options),
        team_(options.team),
        yellow_(own == ubersim::Team::Yellow),
        team_code_(yellow_ ? ubersim::team_t::YELLOW : ubersim::team_t::BLUE),
        bus_(bus),
        radio_channel_(ubersim::channel_name(channels, ubersim::topics::kRadio.of(own))),
        world_(yellow_),
        referee_(yellow_) {}

  const demo::TeamSetup& setup() const { return team_; }
  std::int64_t packets() const { return sequence_; }

  void on_geometry(const ubersim::vision_geometry_t& geometry) {
    team_.field_length = geometry.field.field_length;
    team_.field_width = geometry.field.field_width;
  }

  void on_referee(const ubersim::referee_t& referee) { referee_.update(referee); }

  void on_frame(const ubersim::vision_frame_t& frame) {
    if (frame.t_capture + 1.0 < world_.now()) {  // the simulation was reset
      world_ = demo::WorldModel(yellow_);
      last_sent_ = -1e9;
    }
    world_.update(frame);
    referee_.advance_to(frame.t_sent);
    team_.keeper_id = referee_.goalkeeper();
    if (world_.now() - last_sent_ < 1.0 / options_.rate - 1e-9) {
      if (options_.sync) send({}, frame.t_capture);  // nothing to send: the answer says so
      return;
    }
    last_sent_ = world_.now();
    world_.forget_older_than(1.0);
    send(commands(), options_.sync ? frame.t_capture : world_.now());
  }

 private:
  std::vector<ubersim::robot_command_t> commands() const {
    if (options_.mode == "positions") return demo::hold_positions(world_, team_);
    if (options_.mode == "figure8") {
      return demo::figure_eights(world_, team_, options_.figure8_speed, options_.figure8_size);
    }
    return play_by_the_rules(referee_.mode(), world_, team_);
  }

  void send(std::vector<ubersim::robot_command_t> commands, double t_sent) {
    ubersim::radio_packet_t packet{};
    packet.team = team_code_;
    packet.sequence = sequence_++;
    packet.t_sent = t_sent;
    packet.commands = std::move(commands);
    packet.num_commands = static_cast<int32_t>(packet.commands.size());
    bus_.publish(radio_channel_, packet);
  }

  const Options& options_;
  demo::TeamSetup team_;
  bool yellow_;
  std::int8_t team_code_;
  ubersim::MessageBus& bus_;
  std::string radio_channel_;  // RADIO_<TEAM>
  demo::WorldModel world_;
  demo::RefereeFollower referee_;
  double last_sent_ = -1e9;
  std::int64_t sequence_ = 0;
};

// The wiring block: the team on the process host.
int run(const Options& options, ubersim::Team own) {
  using ubersim::ProcessHost;
  namespace topics = ubersim::topics;
  const std::string name = std::string("demo_") + ubersim::team_name(own);
  ProcessHost host(options.common, name);
  DemoTeam team(options, own, host.bus(), host.channels());
  ubersim::subscribe(host.bus(), host.channels(), topics::kVisionGeometry,
                     [&](const ubersim::vision_geometry_t& g) { team.on_geometry(g); });
  ubersim::subscribe(host.bus(), host.channels(), topics::kReferee,
                     [&](const ubersim::referee_t& r) { team.on_referee(r); });
  ubersim::subscribe(host.bus(), host.channels(), topics::kVision,
                     [&](const ubersim::vision_frame_t& frame) { team.on_frame(frame); });
  spdlog::info("{} team, mode {}, defending the {} goal: listening on {}, sending on {}",
               ubersim::team_name(own), options.mode,
               team.setup().defends < 0 ? "negative-x" : "positive-x",
               ubersim::channel_name(host.channels(), topics::kVision),
               ubersim::channel_name(host.channels(), topics::kRadio.of(own)));
  // Sync mode's registration: said now, again every second (for a radio
  // emulator that starts later), goodbye at the stop.
  std::optional<ubersim::SyncClient> sync_client;
  if (options.sync) {
    sync_client.emplace(host.bus(), host.channels(), own, name);
    sync_client->join(host.now());
    host.after_wake([&](ProcessHost::Clock::time_point now) { sync_client->tick(now); });
    host.at_stop([&] { sync_client->leave(); });
  }
  host.at_stop([&] { spdlog::info("stopped after {} packets", team.packets()); });
  return host.run(std::chrono::milliseconds(100));
}

void add_options(CLI::App& app, Options& o) {
  ubersim::add_common_options(app, o.common);
  app.add_option("--team", o.team_text, "yellow | blue")->capture_default_str();
  app.add_option("--mode", o.mode, "play | positions | figure8")
      ->check(CLI::IsMember({"play", "positions", "figure8"}))
      ->capture_default_str();
  app.add_option("--defends", o.defends_text,
                 "negative | positive x goal (default: yellow negative, blue positive)")
      ->check(CLI::IsMember(ubersim::kDefendedSides));
  app.add_option("--rate", o.rate, "commands per second of capture time (Hz)")
      ->capture_default_str()
      ->check(ubersim::greater_than(0));
  app.add_option("--figure8-speed", o.figure8_speed, "m/s")->capture_default_str();
  app.add_option("--figure8-size", o.figure8_size, "m across")->capture_default_str();
  app.add_option("--kick-speed", o.team.kick_speed, "m/s")->capture_default_str();
  app.add_option("--max-speed", o.team.limits.max_speed, "m/s")->capture_default_str();
  app.add_flag("--sync", o.sync,
               "sync client: register on SYNC_CLIENT and answer every vision frame "
               "(docs/sync.md)");
}

int parse_and_run(int argc, char** argv) {
  Options options;
  CLI::App app{"ubersim demo team: drives one team's robots from VISION over RADIO_<TEAM>"};
  add_options(app, options);
  if (const auto stop = ubersim::parse_command_line(app, argc, argv)) return *stop;

  ubersim::Team own{};
  if (!ubersim::parse_team(options.team_text, own)) {
    std::cerr << "demo_team: --team must be yellow or blue\n";
    return 2;
  }
  ubersim::setup_logging(std::string("demo_") + ubersim::team_name(own),
                         options.common.verbosity());
  const bool yellow = own == ubersim::Team::Yellow;
  options.team.defends = options.defends_text.empty()
                             ? (yellow ? -1 : 1)
                             : ubersim::parse_defended_side(options.defends_text);
  return run(options, own);
}

}  // namespace

int main(int argc, char** argv) {
  return ubersim::run_main("demo_team", [&] { return parse_and_run(argc, argv); });
}
