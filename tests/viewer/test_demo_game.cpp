// End to end: the quick start's demo is a refereed game. tools/launch.sh with
// the options tools/demo.sh gives it starts physics, the emulators, both demo
// teams, the automatic referee and the viewer; a headless Chromium shows the
// page. The test puts the ball into a goal (ubersim_referee place-ball, as a
// user could) and reads what the page shows: the score goes up by one, the
// referee stops the game and gives the kick-off to the team that conceded,
// then NORMAL_START, and the ball moves again. A second test plays short games
// and checks that a new one starts when one is over (--repeat-games).
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iterator>
#include <memory>
#include <optional>
#include <sstream>
#include <thread>
#include <ubersim/referee_t.hpp>

#include "cdp_client.hpp"
#include "e2e_support.hpp"
#include "latest_message.hpp"
#include "read_file.hpp"
#include "ubersim/common_options.hpp"
#include "ubersim/message_bus.hpp"

namespace {

using nlohmann::json;

// What tools/demo.sh gives tools/launch.sh besides --open-viewer (a browser of
// the desktop's): DemoScriptRunsTheRefereedGame keeps the two the same.
const std::vector<std::string> kDemoOptions{"--demo", "both", "--referee", "--repeat-games"};

bool port_open(int port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  const bool open = ::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0;
  ::close(fd);
  return open;
}

using ubersim::test::read_file;

// Polls `probe` every 100 ms until `done` holds for its value; returns the last value.
json poll(const std::function<json()>& probe, const std::function<bool(const json&)>& done,
          double timeout_s) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  json value;
  do {
    try {
      value = probe();
      if (done(value)) return value;
    } catch (const std::exception& error) {  // the page is still loading
      value = error.what();
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  } while (std::chrono::steady_clock::now() < deadline);
  return value;
}

TEST(DemoGame, DemoScriptRunsTheRefereedGame) {
  const std::string script = read_file(e2e::source_dir() + "/tools/demo.sh");
  std::string options;
  for (const auto& option : kDemoOptions) options += (options.empty() ? "" : " ") + option;
  EXPECT_NE(script.find("launch.sh\" " + options), std::string::npos)
      << "tools/demo.sh no longer starts launch.sh with '" << options
      << "': make this test start what the demo starts";
}

class DemoGameInBrowser : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string chromium = viewer_test::find_chromium();
    if (chromium.empty()) {
      GTEST_SKIP() << "no chromium (apt-get install chromium, or set UBERSIM_CHROMIUM)";
    }
    std::vector<std::string> options = kDemoOptions;
    for (const char* option : {"--viewer", "--viewer-port"}) options.emplace_back(option);
    options.push_back(std::to_string(port_));
    options.insert(options.end(), {"--seed", "5"});
    launch_ = std::make_unique<e2e::Launch>(options, dir_);
    launch_->processes();
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (!port_open(port_) && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    ASSERT_TRUE(port_open(port_)) << "the viewer never listened; launch said:\n"
                                  << launch_->output();
    try {
      browser_ = std::make_unique<viewer_test::HeadlessChromium>(chromium, dir_.path(""));
    } catch (const std::exception& error) {
      GTEST_SKIP() << "chromium does not run here: " << error.what();
    }
    browser_->open("http://127.0.0.1:" + std::to_string(port_) + "/");
  }
  void TearDown() override {
    browser_.reset();
    if (launch_) launch_->script().stop(10, 2 /* SIGINT, as Ctrl-C */);
  }

  // What the page shows of the game: the panel's text and where it drew the ball.
  json shown() {
    return browser_->evaluate(
        "({yellow: document.getElementById('yellow-score').textContent, "
        "blue: document.getElementById('blue-score').textContent, "
        "stage: document.getElementById('game-stage').textContent, "
        "command: document.getElementById('game-command').textContent, "
        "in_play: viewerState.game && viewerState.game.ball_in_play, "
        "ball: viewerState.ballDrawn})");
  }
  // Polls the page; fails the test naming what it showed last when `done` never holds.
  json wait_for(const std::string& what, const std::function<bool(const json&)>& done,
                double timeout_s) {
    const json last = poll([this] { return shown(); }, done, timeout_s);
    if (!done(last)) {
      ADD_FAILURE() << "the page never showed " << what << "; it showed " << last.dump()
                    << "\nlaunch said:\n"
                    << launch_->output();
    }
    return last;
  }
  // Records every command the page shows until `done` holds for what it shows.
  json watch_commands(const std::string& what, std::vector<std::string>& seen,
                      const std::function<bool(const json&)>& done, double timeout_s) {
    return wait_for(
        what,
        [&](const json& v) {
          if (!v.is_object()) return false;
          const std::string command = v["command"];
          if (seen.empty() || seen.back() != command) seen.push_back(command);
          return done(v);
        },
        timeout_s);
  }

  e2e::TempDir dir_;
  int port_ = 19000 + ::getpid() % 1000;  // own namespace normally; own port otherwise
  std::unique_ptr<e2e::Launch> launch_;
  std::unique_ptr<viewer_test::HeadlessChromium> browser_;
};

int score(const json& shown, const char* team) {
  return std::stoi(shown[team].get<std::string>());
}

TEST_F(DemoGameInBrowser, AfterAGoalTheScoreShowsItAndPlayResumesWithAKickOff) {
  // The first kick-off is taken: the game runs.
  const json running = wait_for(
      "the first half running",
      [](const json& v) {
        return v.is_object() && v["stage"] == "NORMAL_FIRST_HALF" && v["in_play"] == true;
      },
      40);
  ASSERT_FALSE(HasFailure());
  const int yellow_before = score(running, "yellow"), blue_before = score(running, "blue");

  // The ball into the goal at +x: blue's (yellow defends -x by default), so yellow scores.
  const auto [status, output] = [&] {
    ubersim::test::ChildProcess place(
        {e2e::bin_dir() + "/ubersim_referee", "place-ball", "4.6", "0"}, dir_.path("place.out"));
    const int exit_status = place.wait(20);
    return std::make_pair(exit_status, place.log());
  }();
  ASSERT_EQ(status, 0) << output;

  std::vector<std::string> commands;
  const json scored = watch_commands(
      "yellow's score one up", commands,
      [&](const json& v) {
        return score(v, "yellow") == yellow_before + 1 && score(v, "blue") == blue_before;
      },
      10);
  ASSERT_FALSE(HasFailure());
  EXPECT_EQ(scored["stage"], "NORMAL_FIRST_HALF");

  // STOP, the kick-off for the team that conceded, NORMAL_START, and the ball moves.
  const auto seen = [&](const std::string& command) {
    return std::find(commands.begin(), commands.end(), command) != commands.end();
  };
  watch_commands(
      "NORMAL_START after PREPARE_KICKOFF_BLUE", commands,
      [&](const json& v) { return v["command"] == "NORMAL_START" && seen("PREPARE_KICKOFF_BLUE"); },
      15);
  ASSERT_FALSE(HasFailure());
  std::ostringstream sequence;
  for (const auto& command : commands) sequence << command << " ";
  // From the goal on: what the page showed before it (the game running) is not the restart.
  const auto stop = std::find(commands.begin(), commands.end(), "STOP");
  const std::vector<std::string> restart(stop, commands.end());
  EXPECT_EQ(restart, (std::vector<std::string>{"STOP", "PREPARE_KICKOFF_BLUE", "NORMAL_START"}))
      << "commands shown: " << sequence.str();

  // The kick-off spot is the centre; play resumes when the ball leaves it.
  const json resumed = wait_for(
      "the ball moving after the kick-off",
      [&](const json& v) {
        return v.is_object() && v["ball"].is_object() && v["in_play"] == true &&
               std::hypot(v["ball"]["x"].get<double>(), v["ball"]["y"].get<double>()) > 0.15;
      },
      20);
  EXPECT_EQ(score(resumed, "yellow"), yellow_before + 1) << "the goal counted once";
}

using RefereeListener = ubersim::test::LatestMessage<ubersim::referee_t>;

// --repeat-games: when a game is over the demo does not end; a new game starts
// at 0 : 0. Short games at 4x real time.
TEST(DemoGame, ANewGameStartsWhenOneIsOver) {
  e2e::TempDir dir;
  RefereeListener referee("REFEREE");
  std::vector<std::string> options = kDemoOptions;
  options.insert(options.end(), {"--game-length", "2", "--speed", "4", "--seed", "6"});
  e2e::Launch launch(options, dir);
  launch.processes();
  ASSERT_TRUE(referee.wait_for([](const auto& r) { return r.game_over; }, 60))
      << "no game ended; launch said:\n"
      << launch.output();
  const ubersim::referee_t final_state = *referee.latest();
  const double ended = final_state.sim_time;
  EXPECT_EQ(int{final_state.stage}, int{ubersim::referee_t::STAGE_POST_GAME});
  // Between the games the final state stays on REFEREE (for SSL teams through the bridge too).
  EXPECT_TRUE(referee.wait_for([&](const auto& r) { return r.sim_time >= ended + 4.0; }, 30));
  const ubersim::referee_t& later = *referee.latest();
  EXPECT_TRUE(later.game_over) << "at " << later.sim_time << " s";
  EXPECT_EQ(later.yellow_score, final_state.yellow_score);
  EXPECT_EQ(later.blue_score, final_state.blue_score);
  ASSERT_TRUE(referee.wait_for(
      [&](const auto& r) {
        return !r.game_over && r.sim_time > ended && r.yellow_score == 0 && r.blue_score == 0 &&
               r.stage == ubersim::referee_t::STAGE_FIRST_HALF;
      },
      30))
      << "no new game after the one that ended at " << ended << " s; launch said:\n"
      << launch.output();
  EXPECT_GE(referee.latest()->sim_time, ended + 5.0) << "the final score stays up for 5 s";
  EXPECT_TRUE(launch.script().running()) << "the demo ended with its first game";
  const std::string referee_log = read_file(dir.path("logs") + "/referee.log");
  EXPECT_NE(referee_log.find("game 2 starts"), std::string::npos) << referee_log;
}

}  // namespace
