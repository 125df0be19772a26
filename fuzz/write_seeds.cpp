// ubersim_fuzz_seeds DIR: writes the fuzz targets' starting corpora into
// DIR/<target>/, built from real messages (what the SSL protocol's users and
// the viewer's page send), so the fuzzers start from inputs that reach deep
// into the code instead of from nothing. Run at build time; nothing of it is
// committed. The config target's seeds are the shipped config/ files.
#include <grSim_Packet.pb.h>
#include <ssl_simulation_control.pb.h>
#include <ssl_simulation_custom_erforce_realism.pb.h>
#include <ssl_simulation_custom_erforce_robot_spec.pb.h>
#include <ssl_simulation_robot_control.pb.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <ubersim/team_t.hpp>
#include <ubersim/vision_geometry_t.hpp>
#include <vector>

#include "lcm_seeds.hpp"
#include "ubersim/field_config.hpp"
#include "ubersim/ssl_bridge/vision_translation.hpp"

namespace {

namespace fs = std::filesystem;

void write(const fs::path& dir, const std::string& name, const std::string& bytes) {
  fs::create_directories(dir);
  std::ofstream out(dir / name, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw std::runtime_error("cannot write " + (dir / name).string());
}

void write_message(const fs::path& dir, const std::string& name,
                   const google::protobuf::Message& message) {
  write(dir, name, message.SerializeAsString());
}

void ssl_control_seeds(const fs::path& dir) {
  SimulatorCommand ball;
  TeleportBall* b = ball.mutable_control()->mutable_teleport_ball();
  b->set_x(1.5f);
  b->set_y(-0.75f);
  b->set_vx(2.0f);
  b->set_teleport_safely(true);
  b->set_roll(true);
  write_message(dir, "teleport_ball", ball);

  SimulatorCommand robots;
  for (int i = 0; i < 3; ++i) {
    TeleportRobot* r = robots.mutable_control()->add_teleport_robot();
    r->mutable_id()->set_id(static_cast<uint32_t>(i));
    r->mutable_id()->set_team(i == 1 ? YELLOW : BLUE);
    r->set_x(0.5f * static_cast<float>(i));
    r->set_y(-1.0f);
    r->set_orientation(1.0f);
    r->set_v_x(0.2f);
    r->set_present(i != 2);
    r->set_by_force(i == 0);
  }
  robots.mutable_control()->set_simulation_speed(2.0f);
  write_message(dir, "teleport_robots_speed", robots);

  SimulatorCommand stop;
  stop.mutable_control()->set_simulation_speed(0.0f);
  write_message(dir, "pause", stop);

  // The field as the bridge itself sends it (Division B), sent back as a change.
  ubersim::vision_geometry_t geometry{};
  geometry.field =
      ubersim::load_field_config(UBERSIM_FUZZ_CONFIG_DIR, "division_b").to_message(0.0215);
  ubersim::ssl::GeometryExtras extras;
  extras.max_robot_radius = 0.09;
  SimulatorCommand field;
  *field.mutable_config()->mutable_geometry() =
      ubersim::ssl::geometry_packet(geometry, extras).geometry();
  field.mutable_config()->set_vision_port(10020);
  write_message(dir, "geometry", field);

  SimulatorCommand realism;
  RealismConfigErForce erforce;
  erforce.set_stddev_ball_p(0.003f);
  erforce.set_stddev_robot_p(0.002f);
  erforce.set_stddev_robot_phi(0.01f);
  erforce.set_missing_ball_detections(0.05f);
  erforce.set_vision_delay(35000000);
  erforce.set_vision_processing_time(5000000);
  erforce.set_robot_command_loss(0.02f);
  realism.mutable_config()->mutable_realism_config()->add_custom()->PackFrom(erforce);
  write_message(dir, "realism_erforce", realism);

  SimulatorCommand specs;
  for (const Team team : {YELLOW, BLUE}) {
    RobotSpecs* spec = specs.mutable_config()->add_robot_specs();
    spec->mutable_id()->set_team(team);
    if (team == BLUE) spec->mutable_id()->set_id(3);
    spec->set_radius(0.09f);
    spec->set_height(0.147f);
    spec->set_mass(2.3f);
    spec->set_max_linear_kick_speed(6.5f);
    spec->set_max_chip_kick_speed(5.0f);
    spec->set_center_to_dribbler(0.075f);
    RobotLimits* limits = spec->mutable_limits();
    limits->set_acc_speedup_absolute_max(3.0f);
    limits->set_acc_speedup_angular_max(30.0f);
    limits->set_acc_brake_absolute_max(4.0f);
    limits->set_acc_brake_angular_max(40.0f);
    limits->set_vel_absolute_max(3.5f);
    limits->set_vel_angular_max(10.0f);
    RobotWheelAngles* wheels = spec->mutable_wheel_angles();
    wheels->set_front_right(1.0f);
    wheels->set_back_right(2.35f);
    wheels->set_back_left(3.93f);
    wheels->set_front_left(5.28f);
    RobotSpecErForce custom;
    custom.set_shoot_radius(0.067f);
    custom.set_dribbler_width(0.07f);
    spec->add_custom()->PackFrom(custom);
  }
  write_message(dir, "robot_specs", specs);
}

void ssl_robot_control_seeds(const fs::path& dir) {
  RobotControl control;
  for (int i = 0; i < 4; ++i) {
    RobotCommand* c = control.add_robot_commands();
    c->set_id(static_cast<uint32_t>(i));
    RobotMoveCommand* move = c->mutable_move_command();
    if (i == 0) {
      move->mutable_local_velocity()->set_forward(1.0f);
      move->mutable_local_velocity()->set_left(-0.5f);
      move->mutable_local_velocity()->set_angular(2.0f);
    } else if (i == 1) {
      move->mutable_global_velocity()->set_x(0.5f);
      move->mutable_global_velocity()->set_y(0.25f);
      move->mutable_global_velocity()->set_angular(-1.0f);
    } else if (i == 2) {
      MoveWheelVelocity* w = move->mutable_wheel_velocity();
      w->set_front_right(1.0f);
      w->set_back_right(1.1f);
      w->set_back_left(-1.0f);
      w->set_front_left(-1.1f);
    }
    c->set_kick_speed(i == 3 ? 4.0f : 6.5f);
    c->set_kick_angle(i == 3 ? 45.0f : 0.0f);
    c->set_dribbler_speed(1000.0f);
  }
  write_message(dir, "mixed_commands", control);
  RobotControl one;
  one.add_robot_commands()->set_id(6);
  write_message(dir, "one_robot", one);
}

const std::vector<std::string> kControlRequests = {
    R"({"action":"pause"})",
    R"({"action":"resume"})",
    R"({"action":"reset"})",
    R"({"action":"speed","factor":2})",
    R"({"action":"place_ball","x":0.5,"y":-1})",
    R"({"action":"place_robot","team":"blue","id":3,"x":1,"y":2,"orientation":0.5})",
};

// A client frame as a browser sends it: FIN, text, masked.
std::string masked_text_frame(const std::string& payload) {
  std::string frame;
  frame += static_cast<char>(0x81);
  const std::size_t n = payload.size();
  if (n < 126) {
    frame += static_cast<char>(0x80 | n);
  } else {
    frame += static_cast<char>(0x80 | 126);
    frame += static_cast<char>((n >> 8) & 0xff);
    frame += static_cast<char>(n & 0xff);
  }
  const unsigned char mask[4] = {0x12, 0x34, 0x56, 0x78};
  for (unsigned char m : mask) frame += static_cast<char>(m);
  for (std::size_t i = 0; i < n; ++i) frame += static_cast<char>(payload[i] ^ mask[i % 4]);
  return frame;
}

std::string upgrade_request(const std::string& origin) {
  std::string request =
      "GET / HTTP/1.1\r\nHost: 127.0.0.1:8080\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
      "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n";
  if (!origin.empty()) request += "Origin: " + origin + "\r\n";
  return request + "\r\n";
}

void viewer_seeds(const fs::path& http_dir, const fs::path& control_dir) {
  write(http_dir, "get_index", "GET / HTTP/1.1\r\nHost: 127.0.0.1:8080\r\n\r\n");
  write(http_dir, "get_script", "GET /viewer.js?v=1 HTTP/1.1\r\nHost: localhost:8080\r\n\r\n");
  write(http_dir, "post",
        "POST /x HTTP/1.1\r\nHost: 127.0.0.1:8080\r\nContent-Length: 4\r\n\r\nabcd");
  std::string page = upgrade_request("http://127.0.0.1:8080");
  for (const std::string& request : kControlRequests) page += masked_text_frame(request);
  page += std::string("\x88\x82\x01\x02\x03\x04\x02\xea", 8);  // close 1000, masked
  write(http_dir, "page_requests", page);
  write(http_dir, "script_requests", upgrade_request("") + masked_text_frame(kControlRequests[3]));
  write(http_dir, "other_origin", upgrade_request("http://example.org") + masked_text_frame("{}"));
  for (std::size_t i = 0; i < kControlRequests.size(); ++i) {
    write(control_dir, "request_" + std::to_string(i), kControlRequests[i]);
  }
}

// grSim's port: velocities with a kick and the spinner, wheels, a chip, and a
// replacement of robots and the ball.
void ssl_grsim_seeds(const fs::path& dir) {
  grSim_Packet packet;
  grSim_Commands* commands = packet.mutable_commands();
  commands->set_timestamp(1.5);
  commands->set_isteamyellow(true);
  for (uint32_t id = 0; id < 3; ++id) {
    grSim_Robot_Command* c = commands->add_robot_commands();
    c->set_id(id);
    c->set_kickspeedx(id == 0 ? 4.0f : 2.0f);
    c->set_kickspeedz(id == 2 ? 3.0f : 0.0f);
    c->set_veltangent(1.0f);
    c->set_velnormal(-0.5f);
    c->set_velangular(2.0f);
    c->set_spinner(id == 0);
    c->set_wheelsspeed(id == 1);
    if (id == 1) {
      c->set_wheel1(10);
      c->set_wheel2(-10);
      c->set_wheel3(10);
      c->set_wheel4(-10);
    }
  }
  write_message(dir, "commands", packet);
  grSim_Packet replacement;
  grSim_RobotReplacement* robot = replacement.mutable_replacement()->add_robots();
  robot->set_x(1);
  robot->set_y(-1);
  robot->set_dir(90);
  robot->set_id(4);
  robot->set_yellowteam(false);
  robot->set_turnon(false);
  replacement.mutable_replacement()->mutable_ball()->set_x(0.5);
  replacement.mutable_replacement()->mutable_ball()->set_vy(2);
  write_message(dir, "replacement", replacement);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s DIR\n", argv[0]);
    return 2;
  }
  try {
    const fs::path dir = argv[1];
    ssl_control_seeds(dir / "fuzz_ssl_control");
    ssl_robot_control_seeds(dir / "fuzz_ssl_robot_control");
    ssl_grsim_seeds(dir / "fuzz_ssl_grsim");
    viewer_seeds(dir / "fuzz_viewer_http", dir / "fuzz_viewer_control");
    ubersim::fuzz::write_lcm_seeds(dir / "fuzz_lcm_decode", dir / "fuzz_lcm_physics",
                                   dir / "fuzz_lcm_emulators", dir / "fuzz_lcm_consumers");
  } catch (const std::exception& error) {
    std::fprintf(stderr, "ubersim_fuzz_seeds: %s\n", error.what());
    return 1;
  }
  return 0;
}
