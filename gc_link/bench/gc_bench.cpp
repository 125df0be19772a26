// ubersim_gc_bench: how fast a whole game runs in sync mode under the official
// ssl-game-controller in its CI mode (docs/official_gc.md), against the same
// game under the built-in automatic referee in the same run: both through
// tools/launch.sh --sync --demo both (Division B, 2 x 6 robots), and prints
// game seconds (sim time from the start to POST_GAME) per wall second, the
// CPU seconds the whole process set used, and the ratio official / built-in.
#include <sys/resource.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "temp_folder.hpp"
#include "ubersim/child_process.hpp"
#include "ubersim/cli.hpp"
#include "ubersim/process_main.hpp"

namespace {

namespace fs = std::filesystem;

std::string read_file(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string one, five, fifteen;
  in >> one >> five >> fifteen;
  return one + " " + five + " " + fifteen;
}

fs::path own_dir() {
  return fs::read_symlink("/proc/self/exe").parent_path();
}

// CPU seconds (user + system) of every child process reaped so far: launch.sh
// waits for each process it started, so theirs count in it.
double children_cpu() {
  rusage usage{};
  ::getrusage(RUSAGE_CHILDREN, &usage);
  auto seconds = [](const timeval& t) { return t.tv_sec + t.tv_usec * 1e-6; };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

struct Settings {
  std::string source_dir = UBERSIM_SOURCE_DIR;
  std::string game_controller;
  double game_length = 60;
  int seed = 3;
  int repeat = 1;
  std::string url = "udpm://239.255.76.67:7795?ttl=0";
};

struct Game {
  double sim = 0;       // s of sim time at the game's end
  double wall = 0;      // s of wall time of the game, as its referee measured it
  double run_wall = 0;  // s of wall time of the whole launch.sh run (start-up included)
  double cpu = 0;       // CPU seconds of the whole process set
  std::string score;    // "1 : 0"
  std::string details;  // ticks, states judged (the referee's result line)
};

Game play(const Settings& s, const std::string& referee, int index, const fs::path& work) {
  const fs::path logs = work / (referee + "_" + std::to_string(index));
  ::setenv("UBERSIM_BUILD_DIR", own_dir().parent_path().c_str(), 1);
  std::vector<std::string> argv{"/bin/bash",
                                s.source_dir + "/tools/launch.sh",
                                "--sync",
                                "--demo",
                                "both",
                                "--referee",
                                referee,
                                "--game-length",
                                std::to_string(s.game_length),
                                "--seed",
                                std::to_string(s.seed),
                                "--lcm-url",
                                s.url,
                                "--log-dir",
                                logs.string()};
  if (referee == "official") {
    argv.insert(argv.end(), {"--game-controller", s.game_controller});
  }
  const double cpu_before = children_cpu();
  const auto start = std::chrono::steady_clock::now();
  ubersim::ChildProcess launch(argv, (logs.string() + ".out"));
  if (launch.wait(1800) != 0) throw std::runtime_error("launch.sh failed: " + launch.log());
  Game game;
  game.run_wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  game.cpu = children_cpu() - cpu_before;
  const std::string log = read_file(logs / "referee.log");
  std::smatch m;
  const std::regex result(
      R"(result: yellow (\d+) : (\d+) blue \(game over at ([0-9.e+]+) s sim time, ([0-9.e+]+) s wall time, ([^)]*)\))");
  if (!std::regex_search(log, m, result)) {
    throw std::runtime_error("no result line in " + (logs / "referee.log").string());
  }
  game.score = m[1].str() + " : " + m[2].str();
  game.sim = std::stod(m[3]);
  game.wall = std::stod(m[4]);
  game.details = m[5];
  return game;
}

void print_row(const std::string& referee, const Game& g) {
  std::printf("%-9s %7s %8.1f %8.2f %9.1f %9.2f %9.2f %8.3f  %s\n", referee.c_str(),
              g.score.c_str(), g.sim, g.wall, g.sim / g.wall, g.run_wall, g.cpu, g.cpu / g.sim,
              g.details.c_str());
  std::fflush(stdout);
}

int run(int argc, char** argv) {
  CLI::App app{
      "ubersim official GC benchmark: a whole sync-mode game under the official "
      "ssl-game-controller (CI mode) against the built-in referee, in one run"};
  Settings s;
  if (const char* gc = std::getenv("UBERSIM_SSL_GC")) s.game_controller = gc;
  app.add_option("--game-controller", s.game_controller,
                 "the ssl-game-controller binary (default: $UBERSIM_SSL_GC)");
  app.add_option("--game-length", s.game_length, "s of sim time of the game (both halves)")
      ->check(ubersim::greater_than(0))
      ->capture_default_str();
  app.add_option("--seed", s.seed, "seed of physics and the emulators")->capture_default_str();
  app.add_option("--repeat", s.repeat, "games per referee (alternating)")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  app.add_option("--lcm-url", s.url, "LCM URL of the runs (a port of their own)")
      ->capture_default_str();
  app.add_option("--source-dir", s.source_dir, "the ubersim checkout (for tools/launch.sh)")
      ->capture_default_str();
  if (const auto stop = ubersim::parse_command_line(app, argc, argv)) return *stop;
  if (s.game_controller.empty()) {
    std::fprintf(stderr,
                 "ubersim_gc_bench: give --game-controller PATH or set UBERSIM_SSL_GC "
                 "(../shared/tools/build-official-ssl-stack.sh builds it)\n");
    return 2;
  }

  ubersim::test::TempFolder work_dir("ubersim_gc_bench");  // the runs' logs
  std::printf(
      "ubersim official GC benchmark: Division B, 2 x 6 robots, both demo teams, sync mode,\n"
      "--game-length %g (both halves), seed %d, %d game(s) per referee; %ld CPUs online.\n"
      "Target: the official GC at least 8 game seconds per wall second.\n"
      "Load average at start: %s (the machine is shared: figures vary with load).\n\n",
      s.game_length, s.seed, s.repeat, ::sysconf(_SC_NPROCESSORS_ONLN), load_average().c_str());
  std::printf("%-9s %7s %8s %8s %9s %9s %9s %8s  %s\n", "referee", "score", "game [s]", "wall [s]",
              "speed [x]", "run [s]", "CPU [s]", "CPU/game", "referee's figures");
  double official_speed = 0, builtin_speed = 0;
  for (int i = 0; i < s.repeat; ++i) {
    // Alternating, so that a change of load hurts both alike.
    const std::vector<std::string> order = i % 2 == 0
                                               ? std::vector<std::string>{"builtin", "official"}
                                               : std::vector<std::string>{"official", "builtin"};
    for (const std::string& referee : order) {
      const Game game = play(s, referee, i, work_dir.root());
      print_row(referee, game);
      (referee == "official" ? official_speed : builtin_speed) += game.sim / game.wall;
    }
  }
  official_speed /= s.repeat;
  builtin_speed /= s.repeat;
  std::printf(
      "\nofficial GC: %.1f game s per wall s (target >= 8: %s); built-in referee: %.1f; "
      "ratio official / built-in: %.2f\n",
      official_speed, official_speed >= 8 ? "met" : "NOT met", builtin_speed,
      official_speed / builtin_speed);
  std::printf(
      "game: sim time from the start to POST_GAME (the GC's stage clock stops in stoppages, so\n"
      "its game is longer in sim time); wall: the game as its referee timed it; speed: game /\n"
      "wall; run: the whole launch.sh run, start-up included; CPU: user + system seconds of\n"
      "every process of the run; CPU/game: per game second. Load average at the end: %s\n",
      load_average().c_str());
  work_dir.succeeded();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return ubersim::run_main("ubersim_gc_bench", [&] { return run(argc, argv); });
}
