#include "timed_game.hpp"

#include <optional>

#include "read_file.hpp"

namespace e2e {

TimedGame play_timed_game(const TempDir& dir, const std::string& name, const std::string& yellow,
                          const std::string& blue, const std::string& seconds,
                          const std::string& seed, bool hog) {
  const std::string log = dir.path(name + ".lcmlog");
  const std::string logs = dir.path(name + "_logs");
  std::optional<CpuHog> load;
  if (hog) load.emplace();
  Launch launch({"--sync", "--team", "yellow", yellow, "--team", "blue", blue, "--no-tracked",
                 "--duration", seconds, "--seed", seed, "--log", log, "--log-dir", logs},
                dir);
  TimedGame game;
  game.status = launch.script().wait(120);
  game.output = launch.output();
  game.bridge_log = ubersim::test::read_file(logs + "/ssl_bridge.log");
  game.radio_log = ubersim::test::read_file(logs + "/radio.log");
  game.yellow_log = ubersim::test::read_file(logs + "/team_yellow.log");
  game.blue_log = ubersim::test::read_file(logs + "/team_blue.log");
  if (game.status == 0) game.log = read_log_by_channel(log);
  return game;
}

}  // namespace e2e
