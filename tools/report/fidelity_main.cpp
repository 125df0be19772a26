// ubersim_report_fidelity: runs the fidelity experiments of the report
// (acceleration ramps and saturation sweeps, figure-8, ball) against the real
// processes in lockstep, and writes data files plus fidelity.md into --out.
// Exit code 0 when every target is met, 3 when some are missed (the report
// is written either way), 1 on an error.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <set>

#include "acceleration.hpp"
#include "ball.hpp"
#include "figure8.hpp"
#include "report_writer.hpp"
#include "ubersim/cli.hpp"
#include "ubersim/config.hpp"
#include "ubersim/config_paths.hpp"
#include "ubersim/logging.hpp"
#include "ubersim/process_main.hpp"

namespace {

// Every robot type the config folder ships, by name, sorted.
std::vector<std::string> shipped_robot_types(const std::string& config_dir) {
  std::vector<std::string> types;
  for (const auto& file :
       std::filesystem::directory_iterator(std::filesystem::path(config_dir) / "robots")) {
    if (file.path().extension() == ".cfg") types.push_back(file.path().stem().string());
  }
  std::sort(types.begin(), types.end());
  return types;
}

int run(int argc, char** argv) {
  using namespace ubersim::report;
  CLI::App app{"ubersim fidelity report: the paper's experiments against the real process set"};
  std::string out_dir;
  std::string bin_dir = std::filesystem::canonical("/proc/self/exe").parent_path().string();
  std::string config_dir = ubersim::default_config_dir().string();
  std::vector<std::string> types;  // default: every robot type in <config>/robots
  std::vector<std::string> parts = {"ramp", "sweep", "figure8", "ball"};
  std::string physics_config = "default";
  int trials = 5;
  bool quick = false;
  app.add_option("-o,--out", out_dir, "folder for data files and fidelity.md")->required();
  app.add_option("--bin-dir", bin_dir, "where ubersim_physics, _vision, _radio are")
      ->capture_default_str();
  app.add_option("--config-dir", config_dir, "config folder")->capture_default_str();
  app.add_option("--physics-config", physics_config, "physics config (name or path)")
      ->capture_default_str();
  app.add_option("--types", types, "robot types for the acceleration tests")->capture_default_str();
  app.add_option("--parts", parts, "ramp sweep figure8 ball")->capture_default_str();
  app.add_option("--trials", trials, "ramp trials per robot type")->capture_default_str();
  app.add_flag("--quick", quick, "fewer sweep points, kicks and laps (a smoke run)");
  if (const auto stop = ubersim::parse_command_line(app, argc, argv)) return *stop;
  ubersim::setup_logging("report", 0);

  try {
    const std::set<std::string> want(parts.begin(), parts.end());
    if (types.empty()) types = shipped_robot_types(config_dir);
    std::filesystem::create_directories(out_dir);
    const RigPaths paths{bin_dir, config_dir, (std::filesystem::path(out_dir) / "work").string(),
                         physics_config};
    const ExperimentSetup setup(paths);
    FidelityResults results;
    for (const auto& type : types) {
      if (want.count("ramp")) {
        RampSettings s;
        s.robot_type = type;
        s.trials = trials;
        spdlog::info("acceleration ramp: {} ({} trials)", type, s.trials);
        results.ramps.push_back(run_ramp(setup, s));
      }
      if (want.count("sweep")) {
        SweepSettings s;
        s.robot_type = type;
        if (quick) s.fractions = {0.5, 1.4, 1.8};
        spdlog::info("acceleration sweep: {}", type);
        results.sweeps.push_back(run_sweep(setup, s));
      }
    }
    if (want.count("figure8")) {
      for (const bool ideal : {false, true}) {
        Figure8Settings s;
        s.label = ideal ? "ideal" : "cmdragons02";
        s.vision_profile = s.radio_profile = ideal ? "ideal" : "cmdragons02";
        if (quick) s.laps = 2;
        spdlog::info("figure-8: {}", s.label);
        results.figure8.push_back(run_figure8(setup, s));
      }
    }
    if (want.count("ball")) {
      BallSettings s;
      if (quick) {
        s.kick_speeds = {1.0, 3.5, 6.5};
        s.chip_speeds = {3.0, 5.0};
      }
      spdlog::info("ball: {} kicks, {} chips", s.kick_speeds.size(), s.chip_speeds.size());
      results.ball.push_back(run_ball(setup, s));
    }
    write_data_files(out_dir, results);
    const FidelityVerdicts verdicts = decide_fidelity(results);
    write_fidelity_markdown(out_dir, results, verdicts, setup);
    const int missed = verdicts.missed;
    spdlog::info("fidelity report written to {}: {} target check(s) missed", out_dir, missed);
    return missed == 0 ? 0 : 3;
  } catch (const ubersim::ConfigError& e) {
    spdlog::error("configuration: {}", e.what());
    return 1;
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
}

}  // namespace

int main(int argc, char** argv) {
  return ubersim::run_main("ubersim_report_fidelity", [&] { return run(argc, argv); });
}
