// ubersim_ssl_bridge: speaks the RoboCup SSL protocols for ubersim, so SSL
// software written for grSim or the ER-Force simulator runs unchanged:
// SSL-Vision wrapper packets out (from VISION / VISION_GEOMETRY), the SSL
// simulation protocol in (simulation control -> SIM_CONTROL, robot control ->
// RADIO_<TEAM>, feedback from RADIO_FEEDBACK_<TEAM>), and grSim's own protocol
// (grSim_Packet on 20011, Robots_Status back). See docs/ssl_bridge.md; its
// shell (SslBridgeShell) is ssl_bridge_shell.cpp.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "ssl_bridge_shell.hpp"
#include "ubersim/cli.hpp"
#include "ubersim/process_main.hpp"
#include "ubersim/ssl_bridge/bridge.hpp"
#include "ubersim/ssl_bridge/grsim_port.hpp"

namespace {

using ubersim::ssl::SslBridgeOptions;

// Where vision, referee messages and tracked frames go (docs/ssl_bridge.md, "Where the
// multicast goes"); --local-only excludes every interface and TTL option.
void add_multicast_options(CLI::App& app, ubersim::ssl::BridgeOptions& b) {
  auto* local_only = app.add_flag(
      "--local-only", b.local_only,
      "keep vision, tracked frames and referee messages on this host: sent on lo (127.0.0.1) "
      "with TTL 0 only (also when UBERSIM_SSL_LOCAL_ONLY=1)");
  app.add_option("--vision-address", b.vision_address, "SSL-Vision multicast group (or address)")
      ->capture_default_str();
  app.add_option("--vision-port", b.vision_port, "SSL-Vision port")
      ->capture_default_str()
      ->check(ubersim::in_range(1, 65535));
  local_only->excludes(
      app.add_option("--vision-ttl", b.vision_ttl, "multicast TTL (0: this host only)")
          ->capture_default_str()
          ->check(ubersim::in_range(0, 255)));
  local_only->excludes(
      app.add_option("--vision-interface", b.vision_interface,
                     "comma-separated addresses of the interfaces vision packets leave on; "
                     "'default': the interface the kernel routes the group to")
          ->capture_default_str());
  app.add_option("--referee-address", b.referee_address,
                 "where REFEREE goes as SSL Referee messages (multicast group)")
      ->capture_default_str();
  app.add_option("--referee-port", b.referee_port, "referee messages port")->capture_default_str();
  local_only->excludes(
      app.add_option("--referee-ttl", b.referee_ttl, "referee multicast TTL (0: this host only)")
          ->capture_default_str()
          ->check(ubersim::in_range(0, 255)));
  local_only->excludes(app.add_option("--referee-interface", b.referee_interface,
                                      "interfaces referee messages leave on (and are listened "
                                      "for on); default: --vision-interface's"));
  app.add_option("--tracked-address", b.tracked_address, "tracked frames multicast group")
      ->capture_default_str();
  app.add_option("--tracked-port", b.tracked_port, "tracked frames port")
      ->capture_default_str()
      ->check(ubersim::in_range(1, 65535));
  local_only->excludes(app.add_option("--tracked-ttl", b.tracked_ttl,
                                      "tracked frames multicast TTL (0: this host only)")
                           ->capture_default_str()
                           ->check(ubersim::in_range(0, 255)));
  local_only->excludes(app.add_option("--tracked-interface", b.tracked_interface,
                                      "interfaces tracked frames leave on; default: "
                                      "--vision-interface's"));
  app.add_option("--tracked-rate", b.tracked_rate, "tracked frames per second of sim time")
      ->capture_default_str()
      ->check(ubersim::in_range(1.0, 1000.0));
}

// The simulation protocol's ports and its sync mode.
void add_control_options(CLI::App& app, ubersim::ssl::BridgeOptions& b) {
  app.add_option("--listen-address", b.listen_address,
                 "address the simulation and robot control ports are bound to")
      ->capture_default_str();
  app.add_option("--control-port", b.control_port, "simulation control port")
      ->capture_default_str()
      ->check(ubersim::in_range(1, 65535));
  app.add_option("--blue-port", b.blue_port, "blue robot control port")
      ->capture_default_str()
      ->check(ubersim::in_range(1, 65535));
  app.add_option("--yellow-port", b.yellow_port, "yellow robot control port")
      ->capture_default_str()
      ->check(ubersim::in_range(1, 65535));
  app.add_option("--ack-timeout", b.ack_timeout,
                 "seconds to wait for physics' acknowledgement before answering with an error")
      ->capture_default_str()
      ->check(ubersim::in_range(0.01, 60.0));
  app.add_flag("--sync", b.sync,
               "sync mode: each team's first RobotControl registers it as a sync client, then "
               "each RobotControl answers the oldest detection packet not answered yet "
               "(docs/sync.md)");
  app.add_option("--sync-timeout", b.sync_timeout,
                 "sync mode: s of wall time a team may take to answer a detection packet before "
                 "it is dropped")
      ->capture_default_str()
      ->check(ubersim::in_range(0.01, 600.0));
}

// grSim's command port and the robot status it sends back.
void add_grsim_options(CLI::App& app, ubersim::ssl::GrsimOptions& g) {
  app.add_option("--grsim-port", g.port,
                 "grSim's command port (grSim_Packet), on --listen-address; 0: off")
      ->capture_default_str()
      ->check(ubersim::in_range(0, 65535));
  app.add_option("--grsim-blue-status-port", g.blue_status_port,
                 "port the blue robots' grSim status goes to, at the sender's address")
      ->capture_default_str()
      ->check(ubersim::in_range(1, 65535));
  app.add_option("--grsim-yellow-status-port", g.yellow_status_port,
                 "port the yellow robots' grSim status goes to, at the sender's address")
      ->capture_default_str()
      ->check(ubersim::in_range(1, 65535));
  app.add_option("--grsim-command-hold", g.command_hold,
                 "s a team's robots keep their last grSim command while the team sends nothing "
                 "(grSim: 1); 0: for ever")
      ->capture_default_str()
      ->check(ubersim::in_range(0.0, 3600.0));
}

// Team programs the bridge starts under the time shim (docs/timeshim.md).
void add_team_options(CLI::App& app, SslBridgeOptions& options) {
  app.add_option("--team-command", options.team_commands,
                 "COLOUR COMMAND: with --sync, start COMMAND (/bin/sh -c) under the time shim as "
                 "the COLOUR (yellow, blue, or both: one program for both) team's program, a "
                 "timed sync client (repeatable, one per colour)")
      ->type_name("COLOUR COMMAND");
  app.add_option("--team-output-dir", options.bridge.teams.output_dir,
                 "folder for each team command's output (team_<colour>.log); default: the "
                 "bridge's own stdout and stderr");
  app.add_option("--team-grace", options.team_grace,
                 "s of wall time a team's thread may hold sim time back (busy, or blocked in a "
                 "call the time shim does not know) before it is named")
      ->capture_default_str()
      ->check(ubersim::in_range(0.1, 600.0));
  app.add_option("--team-charge-us", options.team_charge_us,
                 "sim time (us) the time shim charges a team's thread per call that does not "
                 "block, after its first 2000 since it last blocked (a polling loop)")
      ->capture_default_str()
      ->check(ubersim::in_range(0.0, 1e6));
  app.add_option("--team-yield-after-ms", options.team_yield_after_ms,
                 "charge (ms) after which such a thread pauses until sim time catches up: "
                 "larger, fewer steps of the group (faster), coarser send times")
      ->capture_default_str()
      ->check(ubersim::in_range(0.0, 1e4));
  app.add_option("--seed", options.bridge.id_seed,
                 "derive the tracked frames' uuid and the referee's source_identifier from this "
                 "seed (reruns send the teams the same bytes); without it they are random")
      ->check(ubersim::whole_number());
  app.add_flag("--team-deterministic", options.bridge.teams.controller.deterministic,
               "run the team programs' threads one at a time in a fixed order (the time shim's "
               "deterministic mode, docs/timeshim.md): reruns identical also for programs whose "
               "threads race at one sim instant; slower");
  app.add_option("--team-protocol", options.team_protocols,
                 "COLOUR PROTOCOL: ssl (default), lcm or grsim: the COLOUR team's --team-command "
                 "speaks the SSL protocols, LCM (VISION, REFEREE, ... in, RADIO_<TEAM> out) on a "
                 "private bus the bridge relays, or grSim's (grSim_Packet to --grsim-port); "
                 "timed (docs/timeshim.md)")
      ->type_name("COLOUR PROTOCOL");
  app.add_option("--team-lcm-url", options.bridge.lcm_door.url,
                 "the LCM teams' private bus (default: the LCM URL's group on the next port, "
                 "ttl=0)");
}

// The --team-command pairs as commands; an error text when they are not valid.
std::string take_team_commands(SslBridgeOptions& options) {
  auto& teams = options.bridge.teams;
  for (const auto& [colour, command] : options.team_commands) {
    if (colour != "yellow" && colour != "blue" && colour != "both") {
      return "--team-command: colour '" + colour + "' is not yellow, blue or both";
    }
    const bool both = colour == "both";
    const ubersim::Team team = colour == "blue" ? ubersim::Team::Blue : ubersim::Team::Yellow;
    for (const auto& known : teams.commands) {
      if (known.both || both || known.team == team) {
        return "--team-command: more than one program for " + colour;
      }
    }
    if (command.empty()) return "--team-command: empty command";
    teams.commands.push_back({team, both, command});
  }
  if (!teams.commands.empty() && !options.bridge.sync) {
    return "--team-command: only with --sync (without it, start the team program yourself)";
  }
  teams.controller.grace =
      std::chrono::milliseconds(static_cast<std::int64_t>(options.team_grace * 1000));
  teams.controller.charge_ns = static_cast<std::int64_t>(options.team_charge_us * 1e3);
  teams.controller.yield_after_ns = static_cast<std::int64_t>(options.team_yield_after_ms * 1e6);
  return "";
}

int parse_and_run(int argc, char** argv) {
  SslBridgeOptions options;
  auto& b = options.bridge;
  CLI::App app{"ubersim SSL protocol bridge: SSL-Vision out, SSL simulation protocol in"};
  ubersim::add_common_options(app, options.common);
  add_multicast_options(app, b);
  add_control_options(app, b);
  app.add_flag("--official-referee", b.official_referee,
               "the official ssl-game-controller referees: its Referee messages on the referee "
               "address go to REFEREE, and ubersim sends none there");
  app.add_flag("--tracked", b.tracked,
               "also send SSL tracked frames (TrackerWrapperPacket) built from ground truth");
  add_grsim_options(app, options.grsim);
  add_team_options(app, options);
  app.add_option("--robot-type", options.robot_type,
                 "robot config for robots added with present = true, and for wheel_velocity")
      ->capture_default_str();
  app.add_option("--ball", options.ball, "ball config whose model the geometry reports")
      ->capture_default_str();
  if (const auto stop = ubersim::parse_command_line(app, argc, argv)) return *stop;
  std::string error = take_team_commands(options);
  if (error.empty()) {
    error = ubersim::ssl::apply_team_protocols(options.team_protocols, options.common.lcm_url,
                                               b.teams, b.lcm_door);
  }
  if (error.empty() && options.grsim.port == 0 && !ubersim::ssl::grsim_teams(b.teams).empty()) {
    error = "--team-protocol grsim: the grSim port is off (--grsim-port 0)";
  }
  if (!error.empty()) {
    std::fprintf(stderr, "ubersim_ssl_bridge: %s\n", error.c_str());
    return 2;
  }

  ubersim::setup_logging("ssl_bridge", options.common.verbosity());
  // Set by tests/run_isolated.sh when it has no network namespace to offer:
  // then nothing may leave this host, whatever the command line says.
  const char* keep_local = std::getenv("UBERSIM_SSL_LOCAL_ONLY");
  if (keep_local != nullptr && std::string(keep_local) == "1" && !b.local_only) {
    spdlog::info("UBERSIM_SSL_LOCAL_ONLY=1: SSL multicast stays on this host (as --local-only)");
    b.local_only = true;
  }
  return ubersim::ssl::run_ssl_bridge(options);
}

}  // namespace

int main(int argc, char** argv) {
  return ubersim::run_main("ubersim_ssl_bridge", [&] { return parse_and_run(argc, argv); });
}
