// ubersim_vision: the overhead-camera vision server, emulated (see vision_shell.hpp).
#include <CLI/CLI.hpp>
#include <cstdint>
#include <cstdio>
#include <exception>

#include "ubersim/cli.hpp"
#include "ubersim/logging.hpp"
#include "ubersim/process_main.hpp"
#include "ubersim/spdlog.hpp"
#include "ubersim/vision/vision_shell.hpp"

namespace {

int run(int argc, char** argv) {
  CLI::App app{
      "ubersim vision emulator: turns ground truth on SIM_STATE into detection frames on "
      "VISION (rate, latency, noise, dropouts, cameras) as the team's real vision server would"};
  ubersim::vision::VisionProcessOptions options;
  ubersim::add_common_options(app, options.common);
  app.add_option("--profile", options.profile,
                 "emulator profile: a name under <config-dir>/vision/ or a .cfg path")
      ->capture_default_str();
  std::uint64_t seed = 0;
  app.add_option("--seed", seed, "seed for every random draw (overrides the profile's SEED)")
      ->check(ubersim::whole_number());
  app.add_option("--field", options.field,
                 "field config to assume until physics reports one on SIM_GEOMETRY");
  if (const auto stop = ubersim::parse_command_line(app, argc, argv)) return *stop;
  if (app.count("--seed") > 0) options.seed = seed;

  ubersim::setup_logging("vision", options.common.verbosity());
  return ubersim::vision::run_vision_process(options);
}

}  // namespace

int main(int argc, char** argv) {
  return ubersim::run_main("ubersim_vision", [&] { return run(argc, argv); });
}
