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
//
// ER-Force's camera model (the realism fields it names) comes on top: a camera
// may see only its region of the field plus an overlap (CameraRegions); its
// reported centre may be off while its field mapping is right
// (camera_position_error: what is above the ground shifts); its detections may
// carry a systematic offset towards the camera (object_position_offset); and a
// ball's reported blob area has noise (ball_area_sigma).
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <ubersim/vision_frame_t.hpp>
#include <vector>

#include "ubersim/vision/ball_occlusion.hpp"
#include "ubersim/vision/camera_regions.hpp"
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
  // (camera_position_error and object_position_offset included.)
  void set_model(const VisionProfile& profile, const CameraProfile& camera);
  // Which part of the field this camera sees (its index among the cameras).
  void set_region(const CameraRegions& regions, std::size_t index) {
    regions_ = regions;
    region_index_ = index;
  }

  // The calibration the vision system reports: the believed camera, its
  // centre moved by the camera position error.
  camera_calibration_t reported_calibration() const;
  // The pinhole area of a ball of `radius` centred at `centre` (px^2).
  double ball_area(const Eigen::Vector3d& centre, double radius) const;

  // Draws on from where `other` (this camera before a change of its pose) stopped.
  void continue_streams_of(const CameraDetector& other) { random_ = other.random_; }

  int id() const { return id_; }
  const PinholeCamera& truth() const { return truth_; }
  const PinholeCamera& believed() const { return believed_; }

 private:
  // Where the vision system places a true point it assumes to be at height
  // `assumed_height`; empty when this camera does not see the point.
  std::optional<Eigen::Vector2d> locate(const Eigen::Vector3d& point, double assumed_height) const;
  std::optional<Eigen::Vector2d> locate(const Eigen::Vector2d& pixel, double assumed_height) const;
  // In the image of the true camera and in this camera's region.
  bool sees(const Eigen::Vector3d& point) const;
  bool in_region(const Eigen::Vector2d& ground_point) const {
    return regions_.contains(region_index_, ground_point);
  }
  float confidence(double mean);
  void detect_robot(const WorldSnapshot::Robot& robot, vision_frame_t& frame);
  void detect_ball(const WorldSnapshot& world, vision_frame_t& frame);
  void add_false_balls(const WorldSnapshot& world, vision_frame_t& frame);
  vision_ball_t make_ball(const Eigen::Vector2d& position, double radius, double confidence_mean,
                          double area);

  int id_;
  PinholeCamera truth_;
  PinholeCamera believed_;
  VisionProfile profile_;          // a copy: the detection model's parameters
  double processing_time_;         // s
  double false_ball_probability_;  // per robot in view, per frame
  Eigen::Vector3d position_error_ = Eigen::Vector3d::Zero();  // m, reported minus believed centre
  Eigen::Vector2d object_offset_ = Eigen::Vector2d::Zero();   // m, added to every detection
  CameraRegions regions_;
  std::size_t region_index_ = 0;
  BallOcclusion occlusion_;
  RandomSource random_;
};

}  // namespace ubersim::vision
