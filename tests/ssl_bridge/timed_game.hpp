#pragma once
// A sync-mode game of two unchanged team programs under the time shim
// (tools/launch.sh --sync --team yellow 'COMMAND' --team blue 'COMMAND'),
// recorded, with its logs: what test_timed_teams and test_lcm_timed_teams play.
#include <map>
#include <string>

#include "e2e_support.hpp"
#include "sync_logs.hpp"

namespace e2e {

struct TimedGame {
  int status = -1;  // the launch script's exit status
  std::string output, bridge_log, radio_log, yellow_log, blue_log;
  std::map<std::string, ChannelLog> log;  // by channel; empty unless status is 0
};

// `seconds` of sim time with `seed`, the teams' commands as --team takes them,
// recorded into NAME.lcmlog with the processes' logs in NAME_logs (both in
// `dir`), beside a CPU hog when `hog`.
TimedGame play_timed_game(const TempDir& dir, const std::string& name, const std::string& yellow,
                          const std::string& blue, const std::string& seconds,
                          const std::string& seed, bool hog);

}  // namespace e2e
