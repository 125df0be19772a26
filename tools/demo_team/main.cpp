// ubersim_demo_team: a small control program written only against VISION and
// RADIO_<TEAM> — the interface a team's own software has on the real field.
// It acts on each vision frame (throttled to --rate in capture time, so it
// behaves the same at any simulation speed) and sends one radio packet.
// With --sync it is a sync client (docs/sync.md): it registers on SYNC_CLIENT
// and answers every frame, with an empty packet when it has nothing to send.
#include <CLI/CLI.hpp>
#include <chrono>
#include <ubersim/radio_packet_t.hpp>
#include <ubersim/referee_t.hpp>
#include <ubersim/sync_client_t.hpp>
#include <ubersim/team_t.hpp>
#include <ubersim/vision_frame_t.hpp>
#include <ubersim/vision_geometry_t.hpp>

#include "behaviour.hpp"
#include "referee_rules.hpp"
#include "ubersim/cli.hpp"
#include "ubersim/logging.hpp"
#include "ubersim/message_bus.hpp"
#include "ubersim/shutdown.hpp"

namespace {

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

}  // namespace

int main(int argc, char** argv) {
  ubersim::CommonOptions common;
  std::string team_text = "yellow";
  std::string mode = "play";
  std::string defends_text;
  double rate = 60.0;
  double figure8_speed = 0.8;
  double figure8_size = 1.0;
  bool sync = false;
  demo::TeamSetup team;

  CLI::App app{"ubersim demo team: drives one team's robots from VISION over RADIO_<TEAM>"};
  ubersim::add_common_options(app, common);
  app.add_option("--team", team_text, "yellow | blue")->capture_default_str();
  app.add_option("--mode", mode, "play | positions | figure8")
      ->check(CLI::IsMember({"play", "positions", "figure8"}))
      ->capture_default_str();
  app.add_option("--defends", defends_text,
                 "negative | positive x goal (default: yellow negative, blue positive)")
      ->check(CLI::IsMember({"negative", "positive"}));
  app.add_option("--rate", rate, "commands per second of capture time (Hz)")
      ->capture_default_str()
      ->check(ubersim::greater_than(0));
  app.add_option("--figure8-speed", figure8_speed, "m/s")->capture_default_str();
  app.add_option("--figure8-size", figure8_size, "m across")->capture_default_str();
  app.add_option("--kick-speed", team.kick_speed, "m/s")->capture_default_str();
  app.add_option("--max-speed", team.limits.max_speed, "m/s")->capture_default_str();
  app.add_flag("--sync", sync,
               "sync client: register on SYNC_CLIENT and answer every vision frame "
               "(docs/sync.md)");
  if (const auto stop = ubersim::parse_command_line(app, argc, argv)) return *stop;

  ubersim::Team own{};
  if (!ubersim::parse_team(team_text, own)) {
    std::cerr << "demo_team: --team must be yellow or blue\n";
    return 2;
  }
  ubersim::setup_logging(std::string("demo_") + ubersim::team_name(own), common.verbosity());
  const bool yellow = own == ubersim::Team::Yellow;
  team.defends = defends_text.empty() ? (yellow ? -1 : 1) : (defends_text == "negative" ? -1 : 1);

  try {
    ubersim::ShutdownSignal shutdown;
    ubersim::MessageBus bus(ubersim::with_receive_buffer(common.lcm_url));
    const auto channels = common.channels();
    demo::WorldModel world(yellow);
    demo::RefereeFollower referee(yellow);
    double last_sent = -1e9;
    std::int64_t sequence = 0;
    const std::string radio_channel = channels.radio(own);
    const std::int8_t team_code = yellow ? ubersim::team_t::YELLOW : ubersim::team_t::BLUE;

    // Sync mode's contract, all of it: say who we are (again every second,
    // for a radio emulator that starts later), and answer every frame with
    // a packet whose t_sent is the frame's t_capture -- empty when there is
    // nothing to send.
    ubersim::sync_client_t hello{};
    hello.team = team_code;
    hello.name = std::string("demo_") + ubersim::team_name(own);
    const std::string sync_channel = channels.extra(ubersim::kSyncClientChannel);
    auto next_hello = std::chrono::steady_clock::now();
    auto answer_nothing = [&](const ubersim::vision_frame_t& frame) {
      ubersim::radio_packet_t nothing{};
      nothing.team = team_code;
      nothing.sequence = sequence++;
      nothing.t_sent = frame.t_capture;
      bus.publish(radio_channel, nothing);
    };

    bus.subscribe<ubersim::vision_geometry_t>(channels(ubersim::Channel::VisionGeometry),
                                              [&](const ubersim::vision_geometry_t& g) {
                                                team.field_length = g.field.field_length;
                                                team.field_width = g.field.field_width;
                                              });
    bus.subscribe<ubersim::referee_t>(channels.referee(),
                                      [&](const ubersim::referee_t& r) { referee.update(r); });
    bus.subscribe<ubersim::vision_frame_t>(
        channels(ubersim::Channel::Vision), [&](const ubersim::vision_frame_t& frame) {
          if (frame.t_capture + 1.0 < world.now()) {  // the simulation was reset
            world = demo::WorldModel(yellow);
            last_sent = -1e9;
          }
          world.update(frame);
          referee.advance_to(frame.t_sent);
          team.keeper_id = referee.goalkeeper();
          if (world.now() - last_sent < 1.0 / rate - 1e-9) {
            if (sync) answer_nothing(frame);
            return;
          }
          last_sent = world.now();
          world.forget_older_than(1.0);

          ubersim::radio_packet_t packet{};
          packet.team = team_code;
          packet.sequence = sequence++;
          packet.t_sent = sync ? frame.t_capture : world.now();
          packet.commands = mode == "positions" ? demo::hold_positions(world, team)
                            : mode == "figure8"
                                ? demo::figure_eights(world, team, figure8_speed, figure8_size)
                                : play_by_the_rules(referee.mode(), world, team);
          packet.num_commands = static_cast<int32_t>(packet.commands.size());
          bus.publish(radio_channel, packet);
        });

    spdlog::info("{} team, mode {}, defending the {} goal: listening on {}, sending on {}",
                 ubersim::team_name(own), mode, team.defends < 0 ? "negative-x" : "positive-x",
                 channels(ubersim::Channel::Vision), channels.radio(own));
    while (!shutdown.requested()) {
      if (sync && std::chrono::steady_clock::now() >= next_hello) {
        bus.publish(sync_channel, hello);
        next_hello += std::chrono::seconds(1);
      }
      bus.wait_and_handle(100, &shutdown);
    }
    if (sync) {
      hello.leaving = true;
      bus.publish(sync_channel, hello);
    }
    spdlog::info("stopped after {} packets", sequence);
    return 0;
  } catch (const std::exception& error) {
    spdlog::error("{}", error.what());
    return 1;
  }
}
