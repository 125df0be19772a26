// ubersim_demo_team: a small control program written only against VISION and
// RADIO_<TEAM> — the interface a team's own software has on the real field.
// It acts on each vision frame (throttled to --rate in capture time, so it
// behaves the same at any simulation speed) and sends one radio packet.
// With --sync it is a sync client (docs/sync.md): it registers on SYNC_CLIENT
// and answers every frame, with an empty packet when it has nothing to send.
// The core is demo_team.cpp, its shell (DemoTeamShell) demo_team_shell.cpp.
#include <CLI/CLI.hpp>
#include <iostream>
#include <string>

#include "demo_team_shell.hpp"
#include "ubersim/cli.hpp"
#include "ubersim/field_side.hpp"
#include "ubersim/logging.hpp"
#include "ubersim/process_main.hpp"

namespace {

using demo::DemoTeamOptions;

void add_options(CLI::App& app, DemoTeamOptions& o) {
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
  DemoTeamOptions options;
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
  return demo::run_demo_team(options, own);
}

}  // namespace

int main(int argc, char** argv) {
  return ubersim::run_main("demo_team", [&] { return parse_and_run(argc, argv); });
}
