// The SSL protocols as a team's software uses them, against the real
// simulation (physics in real time, vision and radio emulators, bridge, all
// processes over real LCM): the client knows only the official definitions
// (generated protobuf classes and raw UDP sockets). Robot specs change the
// robots' size (seen in geometry and detections) and kick limit (seen on the
// ball). ISOLATED: own network namespace.
#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>
#include <ssl_simulation_custom_erforce_realism.pb.h>
#include <ssl_simulation_custom_erforce_robot_spec.pb.h>
#include <ssl_vision_wrapper_tracked.pb.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include "child_process.hpp"
#include "erforce_presets.hpp"
#include "ssl_client.hpp"

namespace {

using ubersim::test::ChildProcess;
using Clock = std::chrono::steady_clock;

const SSL_DetectionRobot* find_blue(const SSL_WrapperPacket& packet, uint32_t id) {
  if (!packet.has_detection()) return nullptr;
  for (const auto& robot : packet.detection().robots_blue()) {
    if (robot.robot_id() == id) return &robot;
  }
  return nullptr;
}

std::string describe(const SimulatorResponse& response) {
  std::string text;
  for (const auto& e : response.errors()) text += e.code() + ": " + e.message() + "\n";
  return text;
}

TeleportRobot* teleport_blue(SimulatorCommand& command, uint32_t id, float x, float y) {
  TeleportRobot* robot = command.mutable_control()->add_teleport_robot();
  robot->mutable_id()->set_id(id);
  robot->mutable_id()->set_team(BLUE);
  robot->set_x(x);
  robot->set_y(y);
  robot->set_orientation(0);
  robot->set_v_x(0);
  robot->set_v_y(0);
  robot->set_v_angular(0);
  return robot;
}

class SslProtocols : public ::testing::Test {
 protected:
  void start(const std::string& vision_profile, std::vector<std::string> bridge_extra = {}) {
    const std::string logs = ::testing::TempDir();
    const std::string src = UBERSIM_SOURCE_DIR;
    vision_ = std::make_unique<ChildProcess>(
        std::vector<std::string>{UBERSIM_VISION_EXE, "--profile", vision_profile, "--seed", "3"},
        logs + "ssl_protocols_vision.log");
    radio_ = std::make_unique<ChildProcess>(
        std::vector<std::string>{UBERSIM_RADIO_EXE, "--profile",
                                 src + "/tests/data/radio_lossless.cfg", "--seed", "3"},
        logs + "ssl_protocols_radio.log");
    std::vector<std::string> argv{UBERSIM_SSL_BRIDGE_EXE};
    for (const std::string& option : ports_.bridge_options()) argv.push_back(option);
    for (const std::string& option : bridge_extra) argv.push_back(option);
    bridge_ = std::make_unique<ChildProcess>(argv, logs + "ssl_protocols_bridge.log");
    ASSERT_TRUE(radio_->wait_for_output("sim time from", 10)) << radio_->log();
    ASSERT_TRUE(vision_->wait_for_output("subscribing", 10)) << vision_->log();
    ASSERT_TRUE(bridge_->wait_for_output("vision to", 10)) << bridge_->log();
    physics_ = std::make_unique<ChildProcess>(
        std::vector<std::string>{UBERSIM_PHYSICS_EXE, "--scenario", "division_b_6v6"},
        logs + "ssl_protocols_physics.log");
    ASSERT_TRUE(vision_rx_.receive_until(
        [](const SSL_WrapperPacket& p) { return find_blue(p, 2) != nullptr; }, 20))
        << physics_->log() << vision_->log() << bridge_->log();
  }

  void TearDown() override {
    if (bridge_) {
      EXPECT_EQ(bridge_->stop(10), 0) << bridge_->log();
    }
  }

  void expect_done(const SimulatorCommand& command) {
    const auto response = ssl_test::command(control_, command);
    ASSERT_TRUE(response.has_value()) << bridge_->log();
    EXPECT_EQ(response->errors_size(), 0) << describe(*response) << physics_->log();
  }

  // Forgets the packets queued so far: what is read next was sent from now on.
  void drain() {
    while (vision_rx_.receive(0.0)) {
    }
  }

  // Mean detected position of blue `id` over `frames` frames.
  std::pair<double, double> mean_position(uint32_t id, int frames) {
    double sx = 0, sy = 0;
    int n = 0;
    vision_rx_.receive_until(
        [&](const SSL_WrapperPacket& p) {
          if (const SSL_DetectionRobot* r = find_blue(p, id)) {
            sx += r->x();
            sy += r->y();
            ++n;
          }
          return n >= frames;
        },
        5);
    EXPECT_EQ(n, frames);
    return {n ? sx / n : 0, n ? sy / n : 0};
  }

  // Pushed against the +y wall, the robot's centre stops one radius short of it.
  double y_against_wall(uint32_t id) {
    SimulatorCommand to_wall;
    teleport_blue(to_wall, id, 0.5f, 50.0f);  // physics keeps it inside the walls
    expect_done(to_wall);
    std::this_thread::sleep_for(std::chrono::milliseconds(300));  // vision latency, settling
    drain();
    return mean_position(id, 6).second;
  }

  // Kicks from a standstill with the ball at the front; the ball's speed (mm/s)
  // over the first frames after it started moving.
  double kicked_ball_speed(float commanded, double center_to_dribbler) {
    SimulatorCommand place;
    teleport_blue(place, 2, 0.0f, -1.0f);
    place.mutable_control()->mutable_teleport_ball()->set_x(
        static_cast<float>(center_to_dribbler + 0.0215 + 0.002));
    place.mutable_control()->mutable_teleport_ball()->set_y(-1.0f);
    place.mutable_control()->mutable_teleport_ball()->set_z(0.0f);
    place.mutable_control()->mutable_teleport_ball()->set_vx(0.0f);
    place.mutable_control()->mutable_teleport_ball()->set_vy(0.0f);
    expect_done(place);
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    drain();
    RobotControl kick;
    RobotCommand* c = kick.add_robot_commands();
    c->set_id(2);
    c->set_kick_speed(commanded);
    c->set_kick_angle(0);
    std::vector<std::pair<double, double>> track;  // (t_capture, x mm)
    const auto end = Clock::now() + std::chrono::seconds(4);
    while (Clock::now() < end && track.size() < 4) {
      ssl_test::control(blue_, kick, 0.05);
      vision_rx_.receive_until(
          [&](const SSL_WrapperPacket& p) {
            if (!p.has_detection() || p.detection().balls_size() == 0) return false;
            const auto& b = p.detection().balls(0);
            const double x0 = (center_to_dribbler + 0.0215 + 0.002) * 1000;
            if (b.x() > x0 + 20 || !track.empty())
              track.emplace_back(p.detection().t_capture(), b.x());
            return true;
          },
          0.1);
    }
    if (track.size() < 2) return 0;
    return (track.back().second - track.front().second) /
           (track.back().first - track.front().first);
  }

  // Standard deviation (mm, pooled over x and y) of every robot's detections
  // around a straight line in time (the robots stand, but creep by a fraction
  // of a mm per second on their wheels), over `seconds` of frames.
  double detection_sigma(double seconds, double* orientation_sigma = nullptr) {
    // (t_capture, x, y, orientation) per robot
    std::map<std::pair<int, uint32_t>, std::vector<std::array<double, 4>>> samples;
    vision_rx_.receive_until(
        [&](const SSL_WrapperPacket& p) {
          if (!p.has_detection()) return false;
          const double t = p.detection().t_capture();
          for (const auto& r : p.detection().robots_blue()) {
            samples[{1, r.robot_id()}].push_back({t, r.x(), r.y(), r.orientation()});
          }
          for (const auto& r : p.detection().robots_yellow()) {
            samples[{0, r.robot_id()}].push_back({t, r.x(), r.y(), r.orientation()});
          }
          return false;
        },
        seconds);
    double sum_sq = 0, sum_sq_phi = 0;
    std::size_t n = 0, n_phi = 0;
    for (auto& [robot, list] : samples) {
      if (list.size() < 4) continue;
      const double first_phi = list.front()[3];
      for (auto& s : list) s[3] = std::remainder(s[3] - first_phi, 2 * M_PI);  // no jump at pi
      // Least-squares line per coordinate; residuals have n - 2 degrees of freedom.
      const double count = static_cast<double>(list.size());
      double mt = 0;
      for (const auto& s : list) mt += s[0] / count;
      double stt = 0;
      for (const auto& s : list) stt += (s[0] - mt) * (s[0] - mt);
      for (int k = 1; k <= 3; ++k) {
        double mk = 0, stk = 0;
        for (const auto& s : list) mk += s[k] / count;
        for (const auto& s : list) stk += (s[0] - mt) * (s[k] - mk);
        const double slope = stt > 0 ? stk / stt : 0;
        double ss = 0;
        for (const auto& s : list) {
          const double r = s[k] - mk - slope * (s[0] - mt);
          ss += r * r;
        }
        (k == 3 ? sum_sq_phi : sum_sq) += ss;
        (k == 3 ? n_phi : n) += list.size() - 2;
      }
    }
    if (orientation_sigma != nullptr) {
      *orientation_sigma = n_phi ? std::sqrt(sum_sq_phi / static_cast<double>(n_phi)) : -1;
    }
    return n ? std::sqrt(sum_sq / static_cast<double>(n)) : -1;
  }

  const ssl_test::TestPorts ports_ = ssl_test::TestPorts::from_environment();
  ssl_test::VisionReceiver vision_rx_{"224.5.23.2", ports_.vision};
  ssl_test::UdpClient control_{ports_.control};
  ssl_test::UdpClient blue_{ports_.blue};
  std::unique_ptr<ChildProcess> vision_, radio_, bridge_, physics_;
};

}  // namespace

TEST_F(SslProtocols, RobotSpecsChangeRadiusInGeometryAndDetectionsAndTheKickLimit) {
  ASSERT_NO_FATAL_FAILURE(start("ideal"));
  float geometry_radius = 0;
  ASSERT_TRUE(vision_rx_.receive_until(
      [&](const SSL_WrapperPacket& p) {
        if (p.has_geometry()) geometry_radius = p.geometry().field().max_robot_radius();
        return p.has_geometry();
      },
      5));
  EXPECT_FLOAT_EQ(geometry_radius, 90.0f);
  const double wall_y_before = y_against_wall(2);
  const double fast = kicked_ball_speed(5.0f, 0.075);

  // Both teams' robots become 70 mm robots; blue 2 also kicks at most 2 m/s.
  SimulatorCommand specs;
  for (Team team : {BLUE, YELLOW}) {
    RobotSpecs* s = specs.mutable_config()->add_robot_specs();
    s->mutable_id()->set_team(team);
    s->set_radius(0.07f);
    s->set_center_to_dribbler(0.06f);
  }
  RobotSpecs* s = specs.mutable_config()->add_robot_specs();
  s->mutable_id()->set_team(BLUE);
  s->mutable_id()->set_id(2);
  s->set_radius(0.07f);
  s->set_center_to_dribbler(0.06f);
  s->set_max_linear_kick_speed(2.0f);
  expect_done(specs);

  geometry_radius = 0;
  EXPECT_TRUE(vision_rx_.receive_until(
      [&](const SSL_WrapperPacket& p) {
        if (p.has_geometry()) geometry_radius = p.geometry().field().max_robot_radius();
        return p.has_geometry() && geometry_radius < 89.0f;
      },
      5));
  EXPECT_FLOAT_EQ(geometry_radius, 70.0f);
  const double wall_y_after = y_against_wall(2);
  // 20 mm less radius: the centre comes 20 mm closer to the wall (ideal vision).
  EXPECT_NEAR(wall_y_after - wall_y_before, 20.0, 3.0)
      << "before " << wall_y_before << " after " << wall_y_after;
  const double limited = kicked_ball_speed(5.0f, 0.06);
  std::printf(
      "radius 90 -> 70 mm: centre %.1f mm closer to the wall; 5 m/s kick: ball at %.0f mm/s "
      "before, %.0f mm/s with max_linear_kick_speed 2\n",
      wall_y_after - wall_y_before, fast, limited);
  EXPECT_GT(fast, 4000.0) << physics_->log();
  EXPECT_LT(limited, 2100.0);
  EXPECT_GT(limited, 1500.0);
}

// What the official simulation controller sends for a team (its
// robot-specs.yaml entry for TIGERs Mannheim at
// 1c9857786bf9f5926e90603744f2da3559bcce38, once per robot id, ER-Force's
// custom type URL) and RC2021's simulate_dribbling = false: physics takes
// both (no error), and the robot kicks a ball that waits in its mouth (the
// mouth's geometry itself is measured in test_physics_kicker_dribbler).
TEST_F(SslProtocols, OfficialRobotSpecsAndGluedDribblingApplyWithoutErrors) {
  ASSERT_NO_FATAL_FAILURE(start("ideal"));
  SimulatorCommand specs;
  for (uint32_t id = 0; id < 16; ++id) {
    RobotSpecs* s = specs.mutable_config()->add_robot_specs();
    s->mutable_id()->set_team(BLUE);
    s->mutable_id()->set_id(id);
    s->set_radius(0.09f);
    s->set_height(0.143f);
    s->set_mass(2.7f);
    s->set_max_linear_kick_speed(8);
    s->set_max_chip_kick_speed(8);
    s->set_center_to_dribbler(0.078f);
    RobotLimits* l = s->mutable_limits();
    l->set_acc_speedup_absolute_max(4.7f);
    l->set_acc_speedup_angular_max(50.8f);
    l->set_acc_brake_absolute_max(5.9f);
    l->set_acc_brake_angular_max(51.6f);
    l->set_vel_absolute_max(3.7f);
    l->set_vel_angular_max(26.2f);
    RobotSpecErForce erforce;
    erforce.set_shoot_radius(0.0715f);
    erforce.set_dribbler_width(0.065f);
    google::protobuf::Any* custom = s->add_custom();
    custom->set_type_url("type.googleapis.com/sslsim.RobotSpecErForce");
    custom->set_value(erforce.SerializeAsString());
  }
  expect_done(specs);
  SimulatorCommand realism;
  RealismConfigErForce glue;
  glue.set_simulate_dribbling(false);
  realism.mutable_config()->mutable_realism_config()->add_custom()->PackFrom(glue);
  expect_done(realism);
  // The ball 2 mm from the kicker face, inside the mouth: it is kicked.
  const double speed = kicked_ball_speed(5.0f, 0.0715);
  std::printf("TIGERs specs: 5 m/s kick from the mouth: ball at %.0f mm/s\n", speed);
  EXPECT_NEAR(speed, 5000.0, 500.0) << physics_->log();
}

// All four of ER-Force's realism presets (its config/simulator-realism files)
// through the running bridge, emulators and physics: each is applied whole.
TEST_F(SslProtocols, EveryErForceRealismPresetIsAcceptedWithoutError) {
  ASSERT_NO_FATAL_FAILURE(start("ideal"));
  for (const std::string preset : {"None", "Friendly", "RC2021", "Realistic"}) {
    SimulatorCommand command;
    command.mutable_config()->mutable_realism_config()->add_custom()->PackFrom(
        ssl_test::erforce_preset(preset));
    const auto response = ssl_test::command(control_, command);
    ASSERT_TRUE(response.has_value()) << preset << bridge_->log();
    EXPECT_EQ(response->errors_size(), 0) << preset;
    for (const auto& e : response->errors()) ADD_FAILURE() << preset << ": " << e.message();
  }
}

TEST_F(SslProtocols, RealismPresetsSetTheDetectionNoiseOnTheVisionPort) {
  ASSERT_NO_FATAL_FAILURE(start("ideal"));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  drain();
  double baseline_phi = 0;
  const double baseline = detection_sigma(1.0, &baseline_phi);
  std::printf("ideal vision: robot position sigma %.4f mm, orientation %.5f rad\n", baseline,
              baseline_phi);
  for (const std::string preset : {"RC2021", "None", "Friendly"}) {
    SimulatorCommand command;
    command.mutable_config()->mutable_realism_config()->add_custom()->PackFrom(
        ssl_test::erforce_preset(preset));
    const auto response = ssl_test::command(control_, command);
    ASSERT_TRUE(response.has_value());
    // Every field of the preset is modelled: no error at all.
    for (const auto& e : response->errors()) ADD_FAILURE() << preset << ": " << e.message();
    std::this_thread::sleep_for(std::chrono::milliseconds(300));  // frames captured before
    drain();
    double phi_sigma = 0;
    const double sigma = detection_sigma(2.5, &phi_sigma);
    const RealismConfigErForce configured = ssl_test::erforce_preset(preset);
    const double expected = configured.stddev_robot_p() * 1000.0;  // mm
    std::printf(
        "%s: robot position sigma %.4f mm (configured %.4f), orientation %.5f rad "
        "(configured %.5f)\n",
        preset.c_str(), sigma, expected, phi_sigma, configured.stddev_robot_phi());
    if (expected == 0) {  // what is left is the robots' own jitter on their wheels
      EXPECT_LT(sigma, 0.05) << preset;
      EXPECT_LT(phi_sigma, 5e-4) << preset;
    } else {
      EXPECT_NEAR(sigma, expected, 0.1 * expected) << preset;
      EXPECT_NEAR(phi_sigma, configured.stddev_robot_phi(), 0.1 * configured.stddev_robot_phi())
          << preset;
    }
  }
}

TEST_F(SslProtocols, GeometryChangesTheFieldAndVisionPortMovesTheOutput) {
  ASSERT_NO_FATAL_FAILURE(start("ideal"));
  SSL_GeometryData seen;
  ASSERT_TRUE(vision_rx_.receive_until(
      [&](const SSL_WrapperPacket& p) {
        if (p.has_geometry()) seen = p.geometry();
        return p.has_geometry();
      },
      5));
  EXPECT_EQ(seen.field().field_length(), 9000);
  // The geometry a client got, with a longer and wider field.
  SimulatorCommand change;
  SSL_GeometryData* geometry = change.mutable_config()->mutable_geometry();
  *geometry->mutable_field() = seen.field();
  geometry->mutable_field()->set_field_length(10400);
  geometry->mutable_field()->set_field_width(7400);
  expect_done(change);
  EXPECT_TRUE(vision_rx_.receive_until(
      [&](const SSL_WrapperPacket& p) {
        return p.has_geometry() && p.geometry().field().field_length() == 10400 &&
               p.geometry().field().field_width() == 7400;
      },
      5))
      << physics_->log();
  // A robot pushed to the wall now stops at the new one: 0.7 m further out.
  const double y = y_against_wall(2);
  EXPECT_NEAR(y, (3700 + 300 - 90), 5.0);

  // vision_port: from now on the packets go to the new port.
  const int moved_port = ports_.vision + 10;
  ssl_test::VisionReceiver moved_rx("224.5.23.2", moved_port);
  SimulatorCommand port;
  port.mutable_config()->set_vision_port(static_cast<uint32_t>(moved_port));
  expect_done(port);
  EXPECT_TRUE(
      moved_rx.receive_until([](const SSL_WrapperPacket& p) { return p.has_detection(); }, 3));
  drain();
  EXPECT_FALSE(vision_rx_.receive(0.5).has_value()) << "still sending to the old port";
}

// The geometry the official ssl-simulation-controller sends for Division A
// (its file, tests/ssl_bridge/data), with the 2026 room behind the goal lines
// as ssl-vision announces it: the whole stack plays on it.
TEST_F(SslProtocols, OfficialDivisionAGeometryIsTheFieldPlayedOn) {
  ASSERT_NO_FATAL_FAILURE(start("ideal"));
  std::ifstream in(std::string(UBERSIM_SOURCE_DIR) +
                   "/tests/ssl_bridge/data/simctl_geometry_div_a.txt");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  SimulatorCommand change;
  SSL_GeometryData* geometry = change.mutable_config()->mutable_geometry();
  ASSERT_TRUE(google::protobuf::TextFormat::ParseFromString(text, geometry));
  geometry->clear_calib();  // the cameras: the vision profile's (another change)
  geometry->mutable_field()->set_boundary_width_goal_line(600);
  expect_done(change);
  SSL_GeometryFieldSize seen;
  EXPECT_TRUE(vision_rx_.receive_until(
      [&](const SSL_WrapperPacket& p) {
        if (p.has_geometry()) seen = p.geometry().field();
        return p.has_geometry() && seen.field_length() == 12000;
      },
      5))
      << physics_->log();
  EXPECT_EQ(seen.field_width(), 9000);
  EXPECT_EQ(seen.boundary_width(), 300);
  EXPECT_EQ(seen.boundary_width_goal_line(), 600);
  EXPECT_EQ(seen.goal_center_to_penalty_mark(), 8000);
  EXPECT_EQ(seen.goal_depth(), 300);
  EXPECT_EQ(seen.goal_height(), 155);
  // A robot sent beyond the touch line stops at the new wall, 0.3 m beyond it
  // (the walls behind the goal lines are out of the one camera's view here;
  // test_physics_field_walls measures them).
  const double y = y_against_wall(2);
  std::printf("robot against the touch-line wall of the official Division A field: %.1f mm\n", y);
  EXPECT_NEAR(y, 4500 + 300 - 90, 5.0);

  // Another ball radius in the geometry becomes the ball's (physics rebuilds it).
  SimulatorCommand bigger_ball = change;
  bigger_ball.mutable_config()->mutable_geometry()->mutable_field()->set_ball_radius(25.0f);
  expect_done(bigger_ball);
  EXPECT_TRUE(vision_rx_.receive_until(
      [](const SSL_WrapperPacket& p) {
        return p.has_geometry() && std::abs(p.geometry().field().ball_radius() - 25.0f) < 1e-3f;
      },
      5))
      << physics_->log();
}

// The official simulation controller's Division A geometry (camera
// calibrations included) through the whole stack: no error, and from then on
// the two cameras it describes decide which camera sees what, as in ER-Force.
TEST_F(SslProtocols, OfficialGeometryCamerasDecideWhichCameraSeesWhat) {
  ASSERT_NO_FATAL_FAILURE(start("ideal"));  // one camera over the whole field
  std::ifstream file(std::string(UBERSIM_SOURCE_DIR) +
                     "/tests/ssl_bridge/data/simctl_geometry_div_a.txt");
  std::stringstream text;
  text << file.rdbuf();
  SimulatorCommand official;
  ASSERT_TRUE(google::protobuf::TextFormat::ParseFromString(
      text.str(), official.mutable_config()->mutable_geometry()));
  // The cameras are this test's; the field sizes are another's (the file's
  // goal_center_to_penalty_mark of 8000 mm is the field part's to answer).
  const auto response = ssl_test::command(control_, official);
  ASSERT_TRUE(response.has_value()) << bridge_->log();
  // The field part applies too (penalty mark 8 m, ...): no error at all.
  for (const auto& e : response->errors()) ADD_FAILURE() << e.code() << ": " << e.message();
  SimulatorCommand place;
  teleport_blue(place, 2, -2.0f, 1.0f);                           // camera 0's half
  teleport_blue(place, 3, 2.0f, -1.0f);                           // camera 1's half
  place.mutable_control()->mutable_teleport_ball()->set_x(0.1f);  // within both overlaps
  place.mutable_control()->mutable_teleport_ball()->set_y(0.0f);
  expect_done(place);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  drain();

  std::map<uint32_t, int> frames, robot_2, robot_3, balls;
  SSL_GeometryData geometry;
  vision_rx_.receive_until(
      [&](const SSL_WrapperPacket& p) {
        if (p.has_geometry()) geometry = p.geometry();
        if (!p.has_detection()) return false;
        const uint32_t camera = p.detection().camera_id();
        ++frames[camera];
        if (find_blue(p, 2) != nullptr) ++robot_2[camera];
        if (find_blue(p, 3) != nullptr) ++robot_3[camera];
        balls[camera] += p.detection().balls_size();
        return false;
      },
      1.5);
  ASSERT_EQ(frames.size(), 2u) << "cameras 0 and 1 only";
  EXPECT_GE(frames[0], 30);  // 30 Hz, the profile's first camera's rate, for both
  EXPECT_GE(frames[1], 30);
  EXPECT_EQ(robot_2, (std::map<uint32_t, int>{{0, frames[0]}}));
  EXPECT_EQ(robot_3, (std::map<uint32_t, int>{{1, frames[1]}}));
  EXPECT_EQ(balls[0], frames[0]);
  EXPECT_EQ(balls[1], frames[1]);
  ASSERT_EQ(geometry.calib_size(), 2);
  EXPECT_FLOAT_EQ(geometry.calib(0).derived_camera_world_tx(), -3010.0f);
  EXPECT_FLOAT_EQ(geometry.calib(1).derived_camera_world_tx(), 3010.0f);
  EXPECT_FLOAT_EQ(geometry.calib(1).derived_camera_world_tz(), 6000.0f);
  EXPECT_FLOAT_EQ(geometry.calib(1).focal_length(), 390.0f);
  EXPECT_FLOAT_EQ(geometry.calib(1).distortion(), 0.2f);
  std::printf(
      "official geometry: camera 0 %d frames (robot 2 in %d), camera 1 %d (robot 3 in %d)\n",
      frames[0], robot_2[0], frames[1], robot_3[1]);
}

namespace {

const SSL_DetectionBall* first_ball(const SSL_WrapperPacket& p) {
  if (!p.has_detection() || p.detection().balls_size() == 0) return nullptr;
  return &p.detection().balls(0);
}

}  // namespace

TEST_F(SslProtocols, TeleportWithEveryOptionAndDriveWithGlobalVelocity) {
  ASSERT_NO_FATAL_FAILURE(start("ideal"));
  // Partial coordinates: only x changes.
  SimulatorCommand partial;
  TeleportRobot* only_x = partial.mutable_control()->add_teleport_robot();
  only_x->mutable_id()->set_id(2);
  only_x->mutable_id()->set_team(BLUE);
  only_x->set_x(-2.0f);
  const double y_before = mean_position(2, 3).second;
  expect_done(partial);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  drain();
  const auto [x_partial, y_partial] = mean_position(2, 3);
  EXPECT_NEAR(x_partial, -2000, 5);
  EXPECT_NEAR(y_partial, y_before, 5);

  // teleport_safely: the ball lands on blue 2, which is pushed out of the way.
  SimulatorCommand safely;
  safely.mutable_control()->mutable_teleport_ball()->set_x(-2.0f);
  safely.mutable_control()->mutable_teleport_ball()->set_y(static_cast<float>(y_partial / 1000));
  safely.mutable_control()->mutable_teleport_ball()->set_teleport_safely(true);
  expect_done(safely);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  drain();
  const auto [x_safe, y_safe] = mean_position(2, 3);
  EXPECT_GT(std::hypot(x_safe + 2000, y_safe - y_partial), 90 + 21.5) << "robot not moved away";

  // roll: a rolling ball keeps its speed; a teleported one slides first and
  // loses about 2/7 of it.
  const auto ball_speed_after = [&](bool roll) {
    SimulatorCommand shot;
    TeleportBall* b = shot.mutable_control()->mutable_teleport_ball();
    b->set_x(-1.0f);
    b->set_y(-2.5f);
    b->set_vx(2.0f);
    b->set_vy(0.0f);
    b->set_roll(roll);
    expect_done(shot);
    std::this_thread::sleep_for(std::chrono::milliseconds(250));
    drain();
    std::vector<std::pair<double, double>> track;
    vision_rx_.receive_until(
        [&](const SSL_WrapperPacket& p) {
          if (const SSL_DetectionBall* ball = first_ball(p))
            track.emplace_back(p.detection().t_capture(), ball->x());
          return track.size() >= 4;
        },
        2);
    if (track.size() < 2) return 0.0;
    return (track.back().second - track.front().second) /
           (track.back().first - track.front().first);
  };
  const double rolling = ball_speed_after(true);
  const double sliding = ball_speed_after(false);
  std::printf("ball 2 m/s: %.0f mm/s rolling, %.0f mm/s teleported without roll (0.25 s later)\n",
              rolling, sliding);
  EXPECT_GT(rolling, 1850.0);
  EXPECT_LT(sliding, 1650.0);

  // by_force: the ball is pushed to (1, 1) over time instead of jumping there.
  SimulatorCommand push;
  TeleportBall* pushed = push.mutable_control()->mutable_teleport_ball();
  pushed->set_x(1.0f);
  pushed->set_y(1.0f);
  pushed->set_by_force(true);
  SimulatorCommand still;
  still.mutable_control()->mutable_teleport_ball()->set_x(0.0f);
  still.mutable_control()->mutable_teleport_ball()->set_y(1.0f);
  expect_done(still);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  expect_done(push);
  drain();
  double first_x = 0;
  ASSERT_TRUE(vision_rx_.receive_until(
      [&](const SSL_WrapperPacket& p) {
        if (const SSL_DetectionBall* ball = first_ball(p)) first_x = ball->x();
        return first_ball(p) != nullptr;
      },
      2));
  EXPECT_LT(first_x, 900.0) << "the ball jumped: teleported, not pushed";
  EXPECT_TRUE(vision_rx_.receive_until(
      [&](const SSL_WrapperPacket& p) {
        const SSL_DetectionBall* ball = first_ball(p);
        return ball != nullptr && std::hypot(ball->x() - 1000, ball->y() - 1000) < 30;
      },
      4))
      << "the ball did not arrive";
  // A robot by force drives itself there.
  SimulatorCommand drive_to;
  TeleportRobot* r = drive_to.mutable_control()->add_teleport_robot();
  r->mutable_id()->set_id(2);
  r->mutable_id()->set_team(BLUE);
  r->set_x(-1.0f);
  r->set_y(-1.5f);
  r->set_orientation(1.0f);
  r->set_by_force(true);
  expect_done(drive_to);
  EXPECT_TRUE(vision_rx_.receive_until(
      [&](const SSL_WrapperPacket& p) {
        const SSL_DetectionRobot* robot = find_blue(p, 2);
        return robot != nullptr && std::hypot(robot->x() + 1000, robot->y() + 1500) < 30 &&
               std::fabs(robot->orientation() - 1.0f) < 0.05f;
      },
      5))
      << "the robot did not drive there";
  SimulatorCommand end;  // nothing but the id: ends the move, no teleport
  TeleportRobot* e = end.mutable_control()->add_teleport_robot();
  e->mutable_id()->set_id(2);
  e->mutable_id()->set_team(BLUE);
  end.mutable_control()->mutable_teleport_ball()->set_by_force(false);
  expect_done(end);

  // present: removed robots disappear, added ones appear.
  SimulatorCommand remove;
  TeleportRobot* gone = remove.mutable_control()->add_teleport_robot();
  gone->mutable_id()->set_id(2);
  gone->mutable_id()->set_team(BLUE);
  gone->set_present(false);
  expect_done(remove);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  drain();
  int frames_without = 0;
  vision_rx_.receive_until(
      [&](const SSL_WrapperPacket& p) {
        if (p.has_detection() && find_blue(p, 2) == nullptr) ++frames_without;
        return frames_without >= 5;
      },
      2);
  EXPECT_EQ(frames_without, 5);
  SimulatorCommand add;
  teleport_blue(add, 9, 0.5f, -2.0f)->set_present(true);
  expect_done(add);
  EXPECT_TRUE(vision_rx_.receive_until(
      [](const SSL_WrapperPacket& p) { return find_blue(p, 9) != nullptr; }, 2));

  // Global velocity: blue 9 drives along +y while facing +x.
  RobotControl sideways;
  RobotCommand* c = sideways.add_robot_commands();
  c->set_id(9);
  MoveGlobalVelocity* v = c->mutable_move_command()->mutable_global_velocity();
  v->set_x(0);
  v->set_y(1.0f);
  v->set_angular(0);
  const auto end_time = Clock::now() + std::chrono::milliseconds(1200);
  while (Clock::now() < end_time) {
    ssl_test::control(blue_, sideways, 0.05);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  drain();
  const auto [x9, y9] = mean_position(9, 2);
  EXPECT_GT(y9 + 2000, 400.0) << "did not drive along +y";
  EXPECT_LT(std::fabs(x9 - 500), 150.0);
}

TEST_F(SslProtocols, TrackedFramesFromGroundTruthWithTheKickedBall) {
  const int tracked_port = ports_.vision + 20;
  ssl_test::VisionReceiver tracked_rx("224.5.23.2", tracked_port);
  ASSERT_NO_FATAL_FAILURE(
      start("ideal", {"--tracked", "--tracked-port", std::to_string(tracked_port)}));
  const auto next_tracked = [&](double timeout) -> std::optional<TrackerWrapperPacket> {
    const auto end = Clock::now() + std::chrono::duration<double>(timeout);
    while (Clock::now() < end) {
      if (auto bytes = tracked_rx.receive_bytes(0.1)) {
        TrackerWrapperPacket packet;
        if (packet.ParseFromString(*bytes)) return packet;
      }
    }
    return std::nullopt;
  };
  auto first = next_tracked(5);
  ASSERT_TRUE(first.has_value()) << bridge_->log();
  const std::string uuid = first->uuid();
  EXPECT_EQ(uuid.size(), 36u);
  EXPECT_EQ(first->source_name(), "ubersim");
  ASSERT_TRUE(first->has_tracked_frame());
  const TrackedFrame& frame = first->tracked_frame();
  EXPECT_EQ(frame.robots_size(), 12);
  ASSERT_EQ(frame.balls_size(), 1);
  ASSERT_EQ(frame.capabilities_size(), 2);
  EXPECT_EQ(frame.capabilities(0), CAPABILITY_DETECT_FLYING_BALLS);
  EXPECT_EQ(frame.capabilities(1), CAPABILITY_DETECT_KICKED_BALLS);
  uint32_t last_number = frame.frame_number();
  double last_time = frame.timestamp();
  for (int i = 0; i < 20; ++i) {
    auto packet = next_tracked(1);
    ASSERT_TRUE(packet.has_value());
    EXPECT_EQ(packet->uuid(), uuid);
    EXPECT_EQ(packet->tracked_frame().frame_number(), last_number + 1);
    EXPECT_GT(packet->tracked_frame().timestamp(), last_time);
    last_number = packet->tracked_frame().frame_number();
    last_time = packet->tracked_frame().timestamp();
  }
  // The tracked robot stands where vision sees it (ideal vision: to a mm).
  const auto [x_seen, y_seen] = mean_position(2, 2);
  auto now = next_tracked(1);
  ASSERT_TRUE(now.has_value());
  bool found = false;
  for (const TrackedRobot& r : now->tracked_frame().robots()) {
    if (r.robot_id().id() != 2 || r.robot_id().team() != BLUE) continue;
    found = true;
    EXPECT_NEAR(r.pos().x() * 1000, x_seen, 2.0);
    EXPECT_NEAR(r.pos().y() * 1000, y_seen, 2.0);
  }
  EXPECT_TRUE(found);

  // A kick: the frames carry the kicked ball, its kicker and where it stops.
  EXPECT_GT(kicked_ball_speed(3.0f, 0.075), 2000.0);
  bool kicked = false;
  const auto end = Clock::now() + std::chrono::seconds(2);
  while (!kicked && Clock::now() < end) {
    auto packet = next_tracked(0.5);
    if (!packet || !packet->tracked_frame().has_kicked_ball()) continue;
    const KickedBall& k = packet->tracked_frame().kicked_ball();
    kicked = true;
    EXPECT_EQ(k.robot_id().id(), 2u);
    EXPECT_EQ(k.robot_id().team(), BLUE);
    EXPECT_NEAR(k.vel().x(), 3.0, 0.4);
    EXPECT_NEAR(k.pos().y(), -1.0, 0.05);
    ASSERT_TRUE(k.has_stop_pos());
    EXPECT_GT(k.stop_pos().x(), k.pos().x() + 1.0);  // it rolls on ahead
    EXPECT_GT(k.stop_timestamp(), k.start_timestamp());
  }
  EXPECT_TRUE(kicked);
}
