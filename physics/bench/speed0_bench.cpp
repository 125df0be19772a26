// ubersim_speed0_bench: what waiting for the vision emulator costs as fast as
// possible (tools/launch.sh --speed 0; docs/vision.md, "As fast as
// possible"), and that no frame is lost. For each scenario it alternates, in
// the same run, the physics alone (ubersim_physics_bench's server figure, as
// ubersim_sync_bench and ubersim_truth_bench use it; and ubersim_physics
// started by launch.sh with no vision and no radio) with the process set at
// --speed 0 under a vision profile (4-camera `modern` by default), without
// and with both demo teams, and prints sim seconds per wall second, the
// ratio to the physics alone, how long physics waited for the vision, and
// the frames the vision lost and captured against the capture instants of
// the run.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
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
using ubersim::physics::bench::median;
using ubersim::physics::bench::physics_alone;
using ubersim::physics::bench::read_file;

namespace fs = std::filesystem;

// Physics alone for a scenario name: "_planar" names the drive model
// (ubersim_physics_bench sets the model itself, on the jointed scenario).
double physics_bench(const std::string& scenario, double seconds, const fs::path& work) {
  const std::string model = scenario.find("planar") != std::string::npos ? "planar" : "jointed";
  const std::string jointed = std::regex_replace(scenario, std::regex("_planar$"), "");
  return physics_alone(jointed, model, seconds, work);
}

struct LaunchOptions {
  std::string source_dir, scenario, profile, url;
  double seconds = 60;
  bool vision = true;  // vision and radio emulators; physics alone without
  bool teams = false;
};

struct LaunchRun {
  double speed = 0;       // sim s per wall s, from physics' first state
  double waited = 0;      // s of wall time physics waited for the vision
  long lost = 0;          // the vision's "frames lost"
  long captured = 0;      // frames the vision captured
  long instants = 0;      // capture instants in [0, seconds] of its cameras
  bool complete = false;  // the vision's summary was found
};

// Capture instants of the cameras the vision log lists ("camera k: R Hz, phase P s") in [0, T].
long capture_instants(const std::string& vision_log, double seconds) {
  long instants = 0;
  const std::regex camera(R"(camera \d+: ([0-9.]+) Hz, phase ([0-9.e-]+) s)");
  for (auto it = std::sregex_iterator(vision_log.begin(), vision_log.end(), camera);
       it != std::sregex_iterator(); ++it) {
    const double rate = std::stod((*it)[1]);
    const double phase = std::stod((*it)[2]);
    instants += static_cast<long>(std::floor((seconds - phase) * rate + 1e-6)) + 1;
  }
  return instants;
}

long summary_count(const std::string& vision_log, const std::string& name) {
  std::smatch match;
  if (!std::regex_search(vision_log, match, std::regex("summary:.*?" + name + " ([0-9]+)"))) {
    return -1;
  }
  return std::stol(match[1]);
}

LaunchRun launch_run(const LaunchOptions& o, const fs::path& work) {
  const fs::path logs = work / "launch";
  fs::remove_all(logs);
  ::setenv("UBERSIM_BUILD_DIR", bench_dir().parent_path().c_str(), 1);
  std::vector<std::string> argv{"/bin/bash",  o.source_dir + "/tools/launch.sh",
                                "--scenario", o.scenario,
                                "--profile",  o.profile,
                                "--speed",    "0",
                                "--duration", std::to_string(o.seconds),
                                "--lcm-url",  o.url,
                                "--log-dir",  logs.string()};
  if (!o.vision) argv.insert(argv.end(), {"--no-vision", "--no-radio"});
  if (o.teams) argv.insert(argv.end(), {"--demo", "both"});
  ubersim::ChildProcess launch(argv, (work / "launch.out").string());
  if (launch.wait(600) != 0) throw std::runtime_error("launch.sh failed: " + launch.log());
  const std::string physics = read_file(logs / "physics.log");
  LaunchRun run;
  std::smatch match;
  // With the vision, physics holds its first state until the vision listens
  // (--wait-for-vision) and times the run from there; alone it starts at once.
  const std::regex from_first(
      R"(as fast as possible: ([0-9.]+) s of sim time in ([0-9.]+) s of wall time from the first)");
  const std::regex whole(R"(physics stopping: \d+ steps, ([0-9.]+) s of sim time in ([0-9.]+) s)");
  if (!std::regex_search(physics, match, from_first) && !std::regex_search(physics, match, whole)) {
    throw std::runtime_error("no figure in physics.log:\n" + physics);
  }
  run.speed = std::stod(match[1]) / std::stod(match[2]);
  if (std::regex_search(physics, match,
                        std::regex(R"(waited ([0-9.]+) s of wall time for the vision)"))) {
    run.waited = std::stod(match[1]);
  }
  if (o.vision) {
    const std::string vision = read_file(logs / "vision.log");
    run.lost = summary_count(vision, "frames lost");
    run.captured = summary_count(vision, "captured");
    run.instants = capture_instants(vision, o.seconds);
    run.complete = run.lost >= 0 && run.captured >= 0;
  }
  return run;
}

struct Column {
  const char* name;
  bool vision, teams;
  std::vector<LaunchRun> runs;
};

void print_scenario(const std::string& scenario, const std::vector<double>& bench,
                    const std::vector<Column>& columns) {
  const double alone = median(bench);
  std::printf("== %s: physics alone (ubersim_physics_bench, server) %.1f x (median of %zu)\n",
              scenario.c_str(), alone, bench.size());
  for (const Column& c : columns) {
    std::vector<double> speeds, waited;
    long lost = 0, captured = 0, instants = 0;
    bool complete = true;
    for (const LaunchRun& r : c.runs) {
      speeds.push_back(r.speed);
      waited.push_back(r.waited);
      lost += r.lost;
      captured += r.captured;
      instants += r.instants;
      complete = complete && r.complete;
    }
    const double speed = median(speeds);
    std::printf("   %-34s %7.1f x = %4.0f %% of physics alone", c.name, speed, 100 * speed / alone);
    if (c.vision) {
      std::printf("; waited for vision %.3f s (median); frames lost %ld%s, captured %ld of %ld",
                  median(waited), lost, complete ? "" : " (a summary missing)", captured, instants);
    }
    std::printf("\n");
  }
  std::fflush(stdout);
}

int run(int argc, char** argv) {
  CLI::App app{"ubersim --speed 0 benchmark: the set with vision against the physics alone"};
  LaunchOptions base;
  base.source_dir = UBERSIM_SOURCE_DIR;
  base.profile = "modern";
  base.url = "udpm://239.255.76.67:7795?ttl=0";
  int repeat = 3;
  std::vector<std::string> scenarios{"division_a_11v11", "division_a_11v11_planar"};
  app.add_option("--source-dir", base.source_dir, "the ubersim checkout (for tools/launch.sh)")
      ->capture_default_str();
  app.add_option("--seconds", base.seconds, "sim seconds per run")->capture_default_str();
  app.add_option("--profile", base.profile, "vision and radio profile")->capture_default_str();
  app.add_option("--repeat", repeat, "runs of each kind, alternated (medians are printed)")
      ->capture_default_str()
      ->check(CLI::Range(1, 100));
  app.add_option("--lcm-url", base.url, "LCM URL of the runs (a port of their own)")
      ->capture_default_str();
  app.add_option("--scenarios", scenarios, "scenarios")->capture_default_str();
  if (const auto stop = ubersim::parse_command_line(app, argc, argv)) return *stop;

  ubersim::test::TempFolder work_dir("ubersim_speed0_bench");  // the runs' logs
  const fs::path& work = work_dir.root();
  std::printf(
      "ubersim --speed 0 benchmark: %g s of sim time per run, profile %s, %d runs of each kind\n"
      "alternated; load average at start %s (the machine is shared: figures vary with load).\n"
      "Target: 0 frames lost, the set with vision at least 90 %% of the physics alone.\n\n",
      base.seconds, base.profile.c_str(), repeat, load_average().c_str());
  for (const std::string& scenario : scenarios) {
    std::vector<double> bench;
    std::vector<Column> columns{{"physics process alone (launch.sh)", false, false, {}},
                                {"physics + vision + radio", true, false, {}},
                                {"the same + both demo teams", true, true, {}}};
    for (int i = 0; i < repeat; ++i) {
      bench.push_back(physics_bench(scenario, base.seconds, work));
      for (Column& c : columns) {
        LaunchOptions o = base;
        o.scenario = scenario;
        o.vision = c.vision;
        o.teams = c.teams;
        c.runs.push_back(launch_run(o, work));
      }
    }
    print_scenario(scenario, bench, columns);
  }
  std::printf(
      "\nspeed: sim seconds per wall second, from physics' first state (with the vision it holds\n"
      "that state until the vision listens); frames lost: the vision's count (capture instants\n"
      "no state reached it for), summed over the runs; captured: frames the vision captured\n"
      "against the capture instants of its cameras in [0, duration], summed.\n");
  work_dir.succeeded();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return ubersim::run_main("ubersim_speed0_bench", [&] { return run(argc, argv); });
}
