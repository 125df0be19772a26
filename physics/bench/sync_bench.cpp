// ubersim_sync_bench: how much of the physics' own speed reaches a team's
// software in sync mode (docs/sync.md). For each scenario it runs, in the same
// run, the physics alone (ubersim_physics_bench's server figure: as fast as
// possible, SIM_STATE on the in-process bus) and then the whole process set
// with both demo teams as sync clients (tools/launch.sh --sync) under each
// emulator profile, and prints sim seconds per wall second, their ratio, and
// how long physics waited at the horizon, per client.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "temp_folder.hpp"
#include "ubersim/child_process.hpp"
#include "ubersim/cli.hpp"
#include "ubersim/process_main.hpp"

namespace {

using ubersim::physics::bench::bench_dir;
using ubersim::physics::bench::bench_program;
using ubersim::physics::bench::load_average;
using ubersim::physics::bench::physics_alone;
using ubersim::physics::bench::read_file;

namespace fs = std::filesystem;

struct SyncRun {
  double sim = 0, wall = 0;
  std::map<std::string, double> waited;  // s of wall time, by what physics waited for
};

// Both demo teams as LCM SyncClients (launch.sh --demo both).
const std::vector<std::string> kSyncClientTeams{"--demo", "both"};

SyncRun sync_run(const std::string& source_dir, const std::string& scenario,
                 const std::string& profile, bool on_demand, double seconds, const std::string& url,
                 const fs::path& work, const std::vector<std::string>& teams = kSyncClientTeams,
                 const std::string& label = "") {
  const fs::path logs =
      work / ("sync_" + scenario + "_" + profile + (on_demand ? "_on_demand" : "") + label);
  ::setenv("UBERSIM_BUILD_DIR", bench_dir().parent_path().c_str(), 1);
  std::vector<std::string> argv{"/bin/bash", source_dir + "/tools/launch.sh", "--sync"};
  argv.insert(argv.end(), teams.begin(), teams.end());
  argv.insert(argv.end(), {"--scenario", scenario, "--profile", profile, "--duration",
                           std::to_string(seconds), "--lcm-url", url, "--log-dir", logs.string()});
  // On demand is physics' default; the other mode must be asked for.
  argv.push_back(on_demand ? "--truth-on-demand" : "--truth-every-step");
  ubersim::ChildProcess launch(argv, (work / "launch.out").string());
  if (launch.wait(600) != 0) throw std::runtime_error("launch.sh failed: " + launch.log());
  const std::string log = read_file(logs / "physics.log");
  SyncRun run;
  std::smatch match;
  if (!std::regex_search(
          log, match,
          std::regex(
              R"(sync: ([0-9.]+) s of sim time in ([0-9.]+) s of wall time from the first)"))) {
    throw std::runtime_error("no sync figure in physics.log:\n" + log);
  }
  run.sim = std::stod(match[1]);
  run.wall = std::stod(match[2]);
  const std::regex waited(R"(sync: waited ([0-9.]+) s for (\S+) \()");
  for (auto it = std::sregex_iterator(log.begin(), log.end(), waited); it != std::sregex_iterator();
       ++it) {
    run.waited[(*it)[2]] += std::stod((*it)[1]);
  }
  return run;
}

// The same demo team logic twice in one run: as LCM SyncClients (--demo
// both: each answers every frame) and unchanged (no --sync) under the time
// shim, on the bridge's private LCM buses (--team COLOUR 'lcm:COMMAND',
// docs/timeshim.md). Prints sim seconds per wall second of each and the ratio.
void shim_case(const std::string& source_dir, const std::string& scenario, double seconds,
               const std::string& url, const fs::path& work) {
  const std::string demo = (bench_dir() / "ubersim_demo_team").string();
  const std::vector<std::string> shimmed{"--team",
                                         "yellow",
                                         "lcm:" + demo + " --team yellow",
                                         "--team",
                                         "blue",
                                         "lcm:" + demo + " --team blue",
                                         "--no-tracked",
                                         "--ssl-local-only"};
  const SyncRun clients = sync_run(source_dir, scenario, "cmdragons02", true, seconds, url, work);
  const SyncRun shim =
      sync_run(source_dir, scenario, "cmdragons02", true, seconds, url, work, shimmed, "_shim");
  const double client_speed = clients.sim / clients.wall;
  const double shim_speed = shim.sim / shim.wall;
  std::printf(
      "\nDemo teams under the time shim against the same demo teams as LCM SyncClients\n"
      "(%s, cmdragons02, SIM_STATE on demand, %g s of sim time each):\n"
      "  as SyncClients        %8.1f x real time\n"
      "  under the time shim   %8.1f x real time\n"
      "  ratio (shim / client) %8.2f\n",
      scenario.c_str(), seconds, client_speed, shim_speed, shim_speed / client_speed);
  std::fflush(stdout);
}

int run(int argc, char** argv) {
  CLI::App app{"ubersim sync benchmark: sync mode's speed against the physics alone"};
  std::string source_dir = UBERSIM_SOURCE_DIR;
  double seconds = 20;
  std::string url = "udpm://239.255.76.67:7791?ttl=0";
  std::vector<std::string> scenarios{"division_a_11v11", "division_a_11v11_planar",
                                     "division_b_6v6"};
  std::vector<std::string> profiles{"cmdragons02", "ideal"};
  std::vector<std::string> truth{"every-step", "on-demand"};
  app.add_option("--source-dir", source_dir, "the ubersim checkout (for tools/launch.sh)")
      ->capture_default_str();
  app.add_option("--seconds", seconds, "sim seconds per run")->capture_default_str();
  app.add_option("--lcm-url", url, "LCM URL of the runs (a port of their own)")
      ->capture_default_str();
  app.add_option("--scenarios", scenarios, "scenarios")->capture_default_str();
  app.add_option("--profiles", profiles, "vision and radio profiles")->capture_default_str();
  app.add_option("--truth", truth,
                 "SIM_STATE every step (physics --truth-every-step), or only on demand (the "
                 "default)")
      ->capture_default_str();
  std::string shim_scenario = "division_b_6v6";
  bool shim_only = false;
  app.add_option("--shim-scenario", shim_scenario,
                 "scenario of the time shim case (demo teams under the shim against the same as "
                 "SyncClients; \"\": none)")
      ->capture_default_str();
  app.add_flag("--shim-only", shim_only, "only the time shim case");
  if (const auto stop = ubersim::parse_command_line(app, argc, argv)) return *stop;

  ubersim::test::TempFolder work_dir("ubersim_sync_bench");  // the runs' logs
  const fs::path& work = work_dir.root();
  if (shim_only) {
    shim_case(source_dir, shim_scenario, seconds, url, work);
    work_dir.succeeded();
    return 0;
  }
  std::printf(
      "ubersim sync benchmark: %g s of sim time per run, both demo teams as sync clients,\n"
      "against the physics alone (ubersim_physics_bench, server, in-process bus) in this run.\n"
      "Targets: at least 70 %% of the physics alone with cmdragons02, 40 %% with ideal.\n"
      "Load average at start: %s (the machine is shared: figures vary with load).\n\n",
      seconds, load_average().c_str());
  std::printf("%-24s %-12s %-11s %10s %10s %7s  %s\n", "scenario", "profile", "SIM_STATE",
              "alone [x]", "sync [x]", "ratio", "physics waited for (s of wall time)");
  for (const std::string& scenario : scenarios) {
    const std::string model = scenario.find("planar") != std::string::npos ? "planar" : "jointed";
    // The bench sets the drive model itself: run its scenario with the jointed robots.
    const std::string alone_scenario = std::regex_replace(scenario, std::regex("_planar$"), "");
    const double alone = physics_alone(alone_scenario, model, seconds, work);
    for (const std::string& profile : profiles) {
      for (const std::string& mode : truth) {
        const SyncRun run =
            sync_run(source_dir, scenario, profile, mode == "on-demand", seconds, url, work);
        const double speed = run.sim / run.wall;
        std::string waited;
        for (const auto& [name, s] : run.waited) {
          char item[96];
          std::snprintf(item, sizeof item, "%s%s %.3f", waited.empty() ? "" : ", ", name.c_str(),
                        s);
          waited += item;
        }
        std::printf("%-24s %-12s %-11s %10.1f %10.1f %6.0f%%  %s\n", scenario.c_str(),
                    profile.c_str(), mode.c_str(), alone, speed, 100 * speed / alone,
                    waited.c_str());
        std::fflush(stdout);
      }
    }
  }
  std::printf(
      "\nSIM_STATE: every step, or on demand (only the states vision, radio and viewer ask for).\n"
      "sync [x]: sim seconds per wall second from physics' first state to the end (start-up "
      "left out);\nratio: sync over alone. Waits: wall time physics spent at the horizon, by "
      "what bounded it\n(a client's name, or vision when the next frame was not published yet).\n");
  if (!shim_scenario.empty()) shim_case(source_dir, shim_scenario, seconds, url, work);
  work_dir.succeeded();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return ubersim::run_main("ubersim_sync_bench", [&] { return run(argc, argv); });
}
