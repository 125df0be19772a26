#pragma once
// One camera of the emulated vision system: where the camera truly hangs, the
// pose the vision system believes it has (they differ by the configured
// calibration error), and the detection model that turns the world as physics
// reports it into that camera's detection frame.
//
// Every detection goes the way light and a real vision server take it: the
// true point is projected by the TRUE camera to a pixel; the vision system
// then intersects the ray through that pixel, as its BELIEVED calibration
// gives it, with the height it assumes for the object (a robot's top, a ball
// resting on the ground). With no calibration error that returns the true
// position exactly; with one it shifts the way a miscalibrated camera does,
// and a ball in the air lands where the camera's ray through it meets the
// ground. Noise is then added in field coordinates, and the reported pixel is
// the believed projection of the reported position, so pixel and position agree.
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <ubersim/vision_frame_t.hpp>
#include <vector>

#include "ubersim/vision/ball_occlusion.hpp"
#include "ubersim/vision/pinhole_camera.hpp"
#include "ubersim/vision/random_source.hpp"
#include "ubersim/vision/robot_sizes.hpp"
#include "ubersim/vision/vision_profile.hpp"

namespace ubersim::vision {

// The world at one physics step, in the form the cameras need it.
struct WorldSnapshot {
  struct Robot {
    std::int8_t team = 0;
    std::int32_t id = 0;
    Eigen::Vector2d position = Eigen::Vector2d::Zero();  // m
    double orientation = 0;                              // rad
    RobotSize size;
  };
  double sim_time = 0;  // s
  std::vector<Robot> robots;
  std::vector<RobotFootprint> footprints;  // same order as robots
  bool ball_present = false;
  Eigen::Vector3d ball = Eigen::Vector3d::Zero();  // centre (m)
  double ball_radius = 0.0215;                     // m
};

class CameraDetector {
 public:
  // seed: the profile's seed; each camera draws from its own stream of it.
  CameraDetector(const CameraProfile& camera, const VisionProfile& profile, std::uint64_t seed);

  vision_frame_t capture(const WorldSnapshot& world, std::int64_t frame_number);
  // New detection model (noise, detection probabilities, false balls) and
  // processing time from the next capture on; the random streams go on.
  void set_model(const VisionProfile& profile, const CameraProfile& camera);

  int id() const { return id_; }
  const PinholeCamera& truth() const { return truth_; }
  const PinholeCamera& believed() const { return believed_; }

 private:
  // Where the vision system places a true point it assumes to be at height
  // `assumed_height`; empty when this camera does not see the point.
  std::optional<Eigen::Vector2d> locate(const Eigen::Vector3d& point, double assumed_height) const;
  std::optional<Eigen::Vector2d> locate(const Eigen::Vector2d& pixel, double assumed_height) const;
  bool sees(const Eigen::Vector3d& point) const;
  float confidence(double mean);
  void detect_robot(const WorldSnapshot::Robot& robot, vision_frame_t& frame);
  void detect_ball(const WorldSnapshot& world, vision_frame_t& frame);
  void add_false_balls(const WorldSnapshot& world, vision_frame_t& frame);
  vision_ball_t make_ball(const Eigen::Vector2d& position, double radius, double confidence_mean);

  int id_;
  PinholeCamera truth_;
  PinholeCamera believed_;
  VisionProfile profile_;          // a copy: the detection model's parameters
  double processing_time_;         // s
  double false_ball_probability_;  // per robot in view, per frame
  BallOcclusion occlusion_;
  RandomSource random_;
};

}  // namespace ubersim::vision
