#include "ubersim/referee/autoref_config.hpp"

#include <cstdint>
#include <string>

#include "ubersim/config_paths.hpp"

namespace ubersim::referee {

std::string team_name_problem(const std::string& name) {
  constexpr std::size_t kMaxLength = 64;  // bytes; a team's name, not a message
  if (name.empty() || name.size() > kMaxLength) return "expected a name of 1..64 bytes";
  for (const char c : name) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7f) return "expected a name without control characters";
  }
  return {};
}

GameConfig load_game_config(const ConfigFile& file) {
  constexpr double kDay = 86400.0;          // s: a longer game is a unit mistake
  constexpr std::int64_t kMaxRobotId = 99;  // a scenario's robot keys: YELLOW_0 .. BLUE_99
  GameConfig c;
  c.game_length = file.real_in("GAME_LENGTH", 0.1, kDay);
  c.halves = static_cast<int>(file.integer_in("HALVES", 1, 2));
  c.half_time_break = file.real_in("HALF_TIME_BREAK", 0.0, kDay);
  c.stop_duration = file.real_in("STOP_DURATION", 0.0, 600.0);
  c.prepare_duration = file.real_in("PREPARE_DURATION", 0.0, 600.0);
  c.restart_timeout = file.real_in("RESTART_TIMEOUT", 0.1, 600.0);
  c.no_progress_time = file.real_in("NO_PROGRESS_TIME", 0.1, 600.0);
  c.progress_distance = file.real_in("PROGRESS_DISTANCE", 0.001, 10.0);
  c.max_robots = static_cast<int>(file.integer_in("MAX_ROBOTS", 1, 16));
  c.max_ball_speed = file.real_in("MAX_BALL_SPEED", 0.1, 100.0);
  c.robot_radius = file.real_in("ROBOT_RADIUS", 0.01, 1.0);
  c.touch_margin = file.real_in("TOUCH_MARGIN", 0.0, 0.5);
  c.keeper_yellow = static_cast<int>(file.integer_in("KEEPER_YELLOW", 0, kMaxRobotId));
  c.keeper_blue = static_cast<int>(file.integer_in("KEEPER_BLUE", 0, kMaxRobotId));
  if (!parse_team(file.string("FIRST_KICKOFF"), c.first_kickoff))
    file.fail("FIRST_KICKOFF", "expected yellow or blue");
  c.yellow_name = file.string("YELLOW_NAME", c.yellow_name);
  c.blue_name = file.string("BLUE_NAME", c.blue_name);
  for (const char* key : {"YELLOW_NAME", "BLUE_NAME"}) {
    if (!file.has(key)) continue;
    if (const std::string problem = team_name_problem(file.string(key)); !problem.empty()) {
      file.fail(key, problem + " (quote a name with spaces: \"TIGERs Mannheim\")");
    }
  }
  file.require_all_used();
  return c;
}

GameConfig load_game_config(const std::string& config_dir, const std::string& name) {
  return load_game_config(ConfigFile::load(resolve_config(config_dir, "referee", name)));
}

}  // namespace ubersim::referee
