// End to end: tools/launch.sh --viewer starts physics, the vision emulator and
// ubersim_viewer over real LCM; a headless Chromium loads the page; the test
// reads back what the page draws (window.viewerState) and compares it with
// SIM_STATE, and works the page's controls with real mouse events to check
// that they reach physics. Saves a screenshot as a test artifact.
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <optional>
#include <thread>
#include <ubersim/sim_state_t.hpp>

#include "cdp_client.hpp"
#include "e2e_support.hpp"
#include "latest_message.hpp"
#include "ubersim/common_options.hpp"
#include "ubersim/message_bus.hpp"

namespace {

using nlohmann::json;

using StateListener = ubersim::test::LatestMessage<ubersim::sim_state_t>;

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

// Everything the tests share: started once, in this order, for the whole suite.
struct Session {
  e2e::TempDir dir;
  int port = 18000 + ::getpid() % 1000;  // own namespace normally; own port otherwise
  std::unique_ptr<e2e::Launch> launch;
  std::unique_ptr<viewer_test::HeadlessChromium> browser;
  std::unique_ptr<StateListener> states;
};
std::unique_ptr<Session> session;
std::string skip_reason;
std::string setup_error;

class ViewerBrowserTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const std::string chromium = viewer_test::find_chromium();
    if (chromium.empty()) {
      skip_reason = "no chromium (apt-get install chromium, or set UBERSIM_CHROMIUM)";
      return;
    }
    session = std::make_unique<Session>();
    session->states = std::make_unique<StateListener>("SIM_STATE");
    session->launch = std::make_unique<e2e::Launch>(
        std::vector<std::string>{"--no-radio", "--viewer", "--viewer-port",
                                 std::to_string(session->port), "--seed", "3"},
        session->dir);
    session->launch->processes();
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (!port_open(session->port) && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    if (!port_open(session->port)) {
      setup_error = "the viewer never listened on port " + std::to_string(session->port) +
                    "; launch said:\n" + session->launch->output();
      return;
    }
    try {
      session->browser =
          std::make_unique<viewer_test::HeadlessChromium>(chromium, session->dir.path(""));
    } catch (const std::exception& error) {
      skip_reason = std::string("chromium does not run here: ") + error.what();
      return;
    }
    session->browser->open("http://127.0.0.1:" + std::to_string(session->port) + "/");
    // Every test starts with the page loaded, connected and drawing frames.
    const auto loaded = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (std::chrono::steady_clock::now() < loaded) {
      try {
        if (session->browser->evaluate("typeof viewerState === 'object' && "
                                       "viewerState.connected && viewerState.framesReceived > 2") ==
            true) {
          return;
        }
      } catch (const std::exception&) {
        // not loaded yet
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    setup_error = "the page never received frames; chromium said:\n" + session->browser->log();
  }
  static void TearDownTestSuite() {
    if (!session) return;
    session->browser.reset();
    if (session->launch) session->launch->script().stop(10, 2 /* SIGINT, as Ctrl-C */);
    session.reset();
  }
  void SetUp() override {
    if (!skip_reason.empty()) GTEST_SKIP() << skip_reason;
    ASSERT_TRUE(setup_error.empty()) << setup_error;
    ASSERT_TRUE(session && session->browser) << "set-up failed";
  }

  viewer_test::HeadlessChromium& browser() { return *session->browser; }
  StateListener& states() { return *session->states; }

  // Polls a page expression until `done` holds for its value.
  json wait_for_page(const std::string& expression, const std::function<bool(const json&)>& done,
                     double timeout_s) {
    const auto deadline =
        std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    json value;
    do {
      try {
        value = browser().evaluate(expression);
        if (done(value)) return value;
      } catch (const std::exception& error) {  // the page is still loading
        value = error.what();
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    } while (std::chrono::steady_clock::now() < deadline);
    ADD_FAILURE() << "page never satisfied the condition; last " << expression << " = "
                  << value.dump();
    return value;
  }

  json page_point(double x, double y) {
    return browser().evaluate("viewerDebug.fieldToPage(" + std::to_string(x) + "," +
                              std::to_string(y) + ")");
  }
  json element_centre(const std::string& id) {
    return browser().evaluate("(() => { const r = document.getElementById('" + id +
                              "').getBoundingClientRect(); return {x: r.left + r.width / 2, "
                              "y: r.top + r.height / 2}; })()");
  }
  void click_element(const std::string& id) {
    const json centre = element_centre(id);
    browser().click(centre["x"], centre["y"]);
  }
  void drag(double from_x, double from_y, double to_x, double to_y) {
    const json from = page_point(from_x, from_y), to = page_point(to_x, to_y);
    browser().mouse("mousePressed", from["x"], from["y"]);
    for (int i = 1; i <= 5; ++i) {
      const double f = i / 5.0;
      browser().mouse("mouseMoved", from["x"].get<double>() * (1 - f) + to["x"].get<double>() * f,
                      from["y"].get<double>() * (1 - f) + to["y"].get<double>() * f);
    }
    browser().mouse("mouseReleased", to["x"], to["y"]);
  }
};

TEST_F(ViewerBrowserTest, PageDrawsFieldRobotsAndVisionDetections) {
  ASSERT_TRUE(states().wait_for([](const auto& s) { return s.num_robots > 0; }, 10));
  const int robots = states().latest()->num_robots;
  EXPECT_EQ(robots, 12) << "division_b_6v6 puts 6 robots per team on the field";
  // Rates are measured over 1 s windows: wait for the first complete one too.
  const json shown = wait_for_page(
      "({frames: viewerState.framesReceived, robots: viewerState.robotsDrawn.length, "
      "vision: viewerState.visionRobotsDrawn, field: document.getElementById('field-name')"
      ".textContent, count: document.getElementById('robot-count').textContent, "
      "state_rate: viewerState.frame.rates.SIM_STATE, vision_rate: "
      "viewerState.frame.rates.VISION})",
      [&](const json& v) {
        return v.is_object() && v["frames"] >= 10 && v["robots"] == robots && v["vision"] > 0 &&
               v["field"] == "division_b" && v["state_rate"] > 10 && v["vision_rate"] > 5;
      },
      20);
  EXPECT_EQ(shown["count"], std::to_string(robots)) << "the panel counts what is drawn";
}

TEST_F(ViewerBrowserTest, PauseButtonPausesPhysicsAndRobotsAreDrawnWhereTheyAre) {
  ASSERT_TRUE(states().wait_for([](const auto& s) { return !s.paused; }, 10));
  click_element("pause-button");
  ASSERT_TRUE(states().wait_for([](const auto& s) { return s.paused; }, 10))
      << "physics did not pause after the page's Pause button";
  const double paused_at = states().latest()->sim_time;
  wait_for_page(
      "document.getElementById('sim-paused').textContent + ' ' + "
      "viewerState.frame.state.sim_time",
      [&](const json& v) {
        return v.is_string() && v.get<std::string>().rfind("paused", 0) == 0 &&
               std::abs(std::stod(v.get<std::string>().substr(7)) - paused_at) < 1e-6;
      },
      10);
  EXPECT_EQ(browser().evaluate("document.getElementById('pause-button').textContent"), "Resume");

  // Paused, the world stands still: what the page drew must be SIM_STATE's robots.
  const json drawn = browser().evaluate("viewerState.robotsDrawn");
  const auto& truth = *states().latest();
  ASSERT_EQ(drawn.size(), truth.robots.size());
  for (const auto& robot : truth.robots) {
    const std::string team = robot.team == 0 ? "yellow" : "blue";
    bool found = false;
    for (const auto& shown : drawn) {
      if (shown["team"] != team || shown["id"] != robot.robot_id) continue;
      found = true;
      EXPECT_NEAR(shown["x"].get<double>(), robot.x, 1e-3) << team << " " << robot.robot_id;
      EXPECT_NEAR(shown["y"].get<double>(), robot.y, 1e-3) << team << " " << robot.robot_id;
      EXPECT_NEAR(shown["orientation"].get<double>(), robot.orientation, 1e-3);
    }
    EXPECT_TRUE(found) << team << " robot " << robot.robot_id << " not drawn";
  }

  const std::string png = browser().screenshot_png();
  ASSERT_GT(png.size(), 1000u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  std::filesystem::create_directories(UBERSIM_VIEWER_ARTIFACT_DIR);
  const std::string path = std::string(UBERSIM_VIEWER_ARTIFACT_DIR) + "/viewer_e2e.png";
  std::ofstream(path, std::ios::binary) << png;
  std::printf("screenshot: %s\n", path.c_str());
}

TEST_F(ViewerBrowserTest, DraggingTheBallPlacesItInPhysics) {
  ASSERT_TRUE(states().wait_for([](const auto& s) { return s.ball_present; }, 10));
  const double ball_x = states().latest()->ball.position[0];
  const double ball_y = states().latest()->ball.position[1];
  const double target_x = 1.2, target_y = -1.0;
  drag(ball_x, ball_y, target_x, target_y);
  // One CSS pixel is about 1 cm at this window size; the page sends where the mouse let go.
  EXPECT_TRUE(states().wait_for(
      [&](const auto& s) {
        return std::hypot(s.ball.position[0] - target_x, s.ball.position[1] - target_y) < 0.03;
      },
      10))
      << "ball at " << states().latest()->ball.position[0] << ", "
      << states().latest()->ball.position[1];
  wait_for_page(
      "viewerState.ballDrawn",
      [&](const json& v) {
        return v.is_object() &&
               std::hypot(v["x"].get<double>() - target_x, v["y"].get<double>() - target_y) < 0.03;
      },
      10);
}

TEST_F(ViewerBrowserTest, DraggingARobotPlacesItInPhysics) {
  ASSERT_TRUE(states().wait_for([](const auto& s) { return s.num_robots > 0; }, 10));
  const ubersim::robot_state_t robot = states().latest()->robots.front();
  const double target_x = -2.0, target_y = 1.5;
  drag(robot.x, robot.y, target_x, target_y);
  EXPECT_TRUE(states().wait_for(
      [&](const auto& s) {
        for (const auto& r : s.robots) {
          if (r.team == robot.team && r.robot_id == robot.robot_id) {
            return std::hypot(r.x - target_x, r.y - target_y) < 0.03 &&
                   std::abs(r.orientation - robot.orientation) < 0.01;
          }
        }
        return false;
      },
      10))
      << "robot " << int{robot.team} << "/" << robot.robot_id << " was not placed";
}

TEST_F(ViewerBrowserTest, SpeedSelectAndResumeReachPhysics) {
  browser().evaluate(
      "(() => { const s = document.getElementById('speed-select'); s.value = '2'; "
      "s.dispatchEvent(new Event('change')); return true; })()");
  EXPECT_TRUE(states().wait_for([](const auto& s) { return s.speed_factor == 2.0; }, 10));
  click_element("pause-button");  // now reads Resume
  EXPECT_TRUE(states().wait_for([](const auto& s) { return !s.paused; }, 10));
  EXPECT_TRUE(wait_for_page(
                  "document.getElementById('sim-speed').textContent",
                  [](const json& v) { return v == "2× real time"; }, 10) == "2× real time");
}

}  // namespace
