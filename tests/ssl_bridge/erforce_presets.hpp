#pragma once
// ER-Force's realism presets as a client sends them: the values of
// robotics-erlangen/framework config/simulator-realism/{None,Friendly,RC2021,Realistic}.txt
// (commit 9814d05763a426f24e5bb134ad7ae2607c64b71e), written out as data.
#include <ssl_simulation_custom_erforce_realism.pb.h>

#include <string>

namespace ssl_test {

inline RealismConfigErForce erforce_preset(const std::string& name) {
  struct Values {
    float ball_p, robot_p, robot_phi, ball_area, overlap, dribbler_detections, camera_error,
        command_loss, response_loss, missing_ball, object_offset, missing_robot;
    long long processing_ns, command_delay_ns;
    bool simulate_dribbling;
  };
  Values v{};
  if (name == "None") {
    v = {0, 0, 0, 0, 0.3f, 0, 0, 0, 0, 0, 0, 0, 5'000'000, 0, true};
  } else if (name == "Friendly") {
    v = {0.0004f, 0.0003f, 0.003f, 1,     1,          0.001f, 0.05f, 0.01f,
         0.01f,   0.05f,   0.02f,  0.02f, 10'000'000, 0,      true};
  } else if (name == "RC2021") {
    v = {0.0010f, 0.0013f, 0.01f, 6.5f, 1,          0.02f, 0,    0.03f,
         0.1f,    0.05f,   0,     0,    10'000'000, 0,     false};
  } else {  // Realistic
    v = {0.0014f, 0.0013f, 0.01f, 6.5f,  1,          0.05f,     0.1f, 0.03f,
         0.1f,    0.05f,   0.02f, 0.02f, 10'000'000, 3'000'000, true};
  }
  RealismConfigErForce r;
  r.set_stddev_ball_p(v.ball_p);
  r.set_stddev_robot_p(v.robot_p);
  r.set_stddev_robot_phi(v.robot_phi);
  r.set_stddev_ball_area(v.ball_area);
  r.set_enable_invisible_ball(true);
  r.set_ball_visibility_threshold(0.4f);
  r.set_camera_overlap(v.overlap);
  r.set_dribbler_ball_detections(v.dribbler_detections);
  r.set_camera_position_error(v.camera_error);
  r.set_robot_command_loss(v.command_loss);
  r.set_robot_response_loss(v.response_loss);
  r.set_missing_ball_detections(v.missing_ball);
  r.set_vision_delay(35'000'000);
  r.set_vision_processing_time(v.processing_ns);
  r.set_simulate_dribbling(v.simulate_dribbling);
  r.set_object_position_offset(v.object_offset);
  r.set_missing_robot_detections(v.missing_robot);
  r.set_command_delay(static_cast<unsigned long long>(v.command_delay_ns));
  return r;
}

}  // namespace ssl_test
