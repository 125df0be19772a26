#include "ubersim/vision/camera_detector.hpp"

#include <algorithm>
#include <cmath>
#include <ubersim/team_t.hpp>

#include "ubersim/angles.hpp"

namespace ubersim::vision {
namespace {

constexpr double kHeadingProbe = 0.05;  // m: second point on a robot's pattern, for its heading

// The direction in which the ER-Force simulator moves every camera's reported
// centre by camera_position_error: (0.3, 0.7, 0.05) normalised in its own
// coordinates, which are the SSL field's turned by 90 deg (SSL x = its y,
// SSL y = -its x; robotics-erlangen/framework src/amun/simulator/simulator.cpp
// and src/core/include/core/coordinates.h).
Eigen::Vector3d erforce_position_error_direction() {
  return Eigen::Vector3d(0.7, -0.3, 0.05).normalized();
}

// ER-Force's object_position_offset of one camera: `strength` metres from the
// field centre towards the camera on the ground (the camera's own distance,
// when it hangs nearer the centre than that).
Eigen::Vector2d object_offset(const Eigen::Vector3d& camera, double strength) {
  const Eigen::Vector2d ground = camera.head<2>();
  if (strength < 1e-9) return Eigen::Vector2d::Zero();
  if (ground.norm() < strength) return ground;
  return ground.normalized() * strength;
}

CameraIntrinsics intrinsics(const CameraProfile& c, double focal_length_error) {
  return CameraIntrinsics{c.focal_length + focal_length_error,
                          c.principal_x,
                          c.principal_y,
                          c.image_width,
                          c.image_height,
                          c.distortion};
}

PinholeCamera true_camera(const CameraProfile& c) {
  return PinholeCamera(c.position, overhead_rotation(c.roll_pitch_yaw), intrinsics(c, 0.0));
}

// The camera as its calibration describes it: the error rotation is applied
// about the camera centre in the field frame.
PinholeCamera believed_camera(const CameraProfile& c) {
  return PinholeCamera(c.position + c.position_error,
                       field_rotation(c.roll_pitch_yaw_error) * overhead_rotation(c.roll_pitch_yaw),
                       intrinsics(c, c.focal_length_error));
}

}  // namespace

CameraDetector::CameraDetector(const CameraProfile& camera, const VisionProfile& profile,
                               std::uint64_t seed)
    : id_(camera.id),
      truth_(true_camera(camera)),
      believed_(believed_camera(camera)),
      profile_(profile),
      processing_time_(camera.processing_time),
      false_ball_probability_(std::min(1.0, profile.false_ball_rate * camera.period())),
      random_(seed, 2 * static_cast<std::uint64_t>(camera.id)) {
  set_model(profile, camera);
}

void CameraDetector::set_model(const VisionProfile& profile, const CameraProfile& camera) {
  profile_ = profile;
  processing_time_ = camera.processing_time;
  false_ball_probability_ = std::min(1.0, profile.false_ball_rate * camera.period());
  position_error_ = erforce_position_error_direction() * profile.camera_position_error;
  object_offset_ = object_offset(truth_.position(), profile.object_position_offset);
}

camera_calibration_t CameraDetector::reported_calibration() const {
  camera_calibration_t calibration = believed_.to_calibration(id_);
  for (int i = 0; i < 3; ++i) calibration.position[i] += position_error_[i];
  return calibration;
}

double CameraDetector::ball_area(const Eigen::Vector3d& centre, double radius) const {
  // A sphere at distance d fills a disc of angular radius asin(r / d): on the
  // image (near the axis) a circle of f r / sqrt(d^2 - r^2) pixels.
  const double d2 = (centre - truth_.position()).squaredNorm();
  if (d2 <= radius * radius) return 0;
  const double f = truth_.intrinsics().focal_length;
  return M_PI * f * f * radius * radius / (d2 - radius * radius);
}

bool CameraDetector::sees(const Eigen::Vector3d& point) const {
  const auto pixel = truth_.project(point);
  return pixel && truth_.in_image(*pixel) && in_region(point.head<2>());
}

std::optional<Eigen::Vector2d> CameraDetector::locate(const Eigen::Vector2d& pixel,
                                                      double assumed_height) const {
  if (position_error_.isZero()) {
    const auto located = believed_.intersect_plane(pixel, assumed_height);
    if (!located) return std::nullopt;
    return located->head<2>();
  }
  // A camera calibrated on the field lines maps the ground right whatever
  // centre it reports; it places an object of height h on the line from its
  // ground point to that centre, so only what is above the ground shifts.
  const auto ground = believed_.intersect_plane(pixel, 0.0);
  if (!ground) return std::nullopt;
  const Eigen::Vector3d centre = believed_.position() + position_error_;
  if (centre.z() <= assumed_height) return std::nullopt;
  const Eigen::Vector3d located = *ground + (centre - *ground) * (assumed_height / centre.z());
  return located.head<2>();
}

std::optional<Eigen::Vector2d> CameraDetector::locate(const Eigen::Vector3d& point,
                                                      double assumed_height) const {
  const auto pixel = truth_.project(point);
  if (!pixel || !truth_.in_image(*pixel)) return std::nullopt;
  return locate(*pixel, assumed_height);
}

float CameraDetector::confidence(double mean) {
  const double value = mean + random_.gaussian(profile_.confidence_sigma);
  return static_cast<float>(std::clamp(value, 0.0, 1.0));
}

void CameraDetector::detect_robot(const WorldSnapshot::Robot& robot, vision_frame_t& frame) {
  const double height = robot.size.height;  // the pattern is on top
  const Eigen::Vector3d top(robot.position.x(), robot.position.y(), height);
  const auto pixel = truth_.project(top);
  if (!pixel || !truth_.in_image(*pixel) || !in_region(robot.position)) return;
  if (!random_.chance(profile_.robot_detection_probability)) return;
  const auto center = locate(*pixel, height);
  // The heading, as the pattern shows it: a point ahead on the top, seen the same way.
  const Eigen::Vector3d ahead =
      top + kHeadingProbe *
                Eigen::Vector3d(std::cos(robot.orientation), std::sin(robot.orientation), 0.0);
  const auto ahead_pixel = truth_.project(ahead);
  const auto ahead_located =
      ahead_pixel ? locate(*ahead_pixel, height) : std::optional<Eigen::Vector2d>();
  if (!center || !ahead_located) return;
  const Eigen::Vector2d direction = *ahead_located - *center;

  vision_robot_t detection{};
  detection.robot_id = robot.id;
  detection.x = center->x() + object_offset_.x() + random_.gaussian(profile_.robot_sigma_x);
  detection.y = center->y() + object_offset_.y() + random_.gaussian(profile_.robot_sigma_y);
  detection.orientation = wrap_angle(std::atan2(direction.y(), direction.x()) +
                                     random_.gaussian(profile_.robot_sigma_orientation));
  detection.confidence = confidence(profile_.robot_confidence);
  const auto reported_pixel = believed_.project(Eigen::Vector3d(detection.x, detection.y, height));
  detection.pixel_x = reported_pixel ? reported_pixel->x() : pixel->x();
  detection.pixel_y = reported_pixel ? reported_pixel->y() : pixel->y();
  if (robot.team == team_t::YELLOW) {
    frame.robots_yellow.push_back(detection);
  } else {
    frame.robots_blue.push_back(detection);
  }
}

vision_ball_t CameraDetector::make_ball(const Eigen::Vector2d& position, double radius,
                                        double confidence_mean, double area) {
  vision_ball_t ball{};
  ball.x = position.x();
  ball.y = position.y();
  ball.confidence = confidence(confidence_mean);
  ball.area = area;
  const auto pixel = believed_.project(Eigen::Vector3d(ball.x, ball.y, radius));
  if (pixel) {
    ball.pixel_x = pixel->x();
    ball.pixel_y = pixel->y();
  }
  return ball;
}

void CameraDetector::detect_ball(const WorldSnapshot& world, vision_frame_t& frame) {
  if (!world.ball_present || !sees(world.ball)) return;
  if (!random_.chance(profile_.ball_detection_probability)) return;
  const BallView view =
      occlusion_.view(truth_.position(), world.ball, world.ball_radius, world.footprints);
  if (view.visible_fraction <= 0 || view.visible_fraction < profile_.ball_min_visible_fraction) {
    return;
  }
  // The vision system assumes every ball rests on the ground (its centre one
  // radius up): a ball in the air is placed where its ray meets that plane.
  const auto seen = locate(view.visible_center, world.ball_radius);
  if (!seen) return;
  const Eigen::Vector2d noisy(
      seen->x() + object_offset_.x() + random_.gaussian(profile_.ball_sigma_x),
      seen->y() + object_offset_.y() + random_.gaussian(profile_.ball_sigma_y));
  // The blob is what is visible of the ball; its measured size is noisy
  // (drawn only when asked for, so profiles without it keep their streams).
  double area = ball_area(world.ball, world.ball_radius);
  if (profile_.ball_area_sigma > 0) area += random_.gaussian(profile_.ball_area_sigma);
  area = std::max(0.0, area * view.visible_fraction);
  frame.balls.push_back(
      make_ball(noisy, world.ball_radius, profile_.ball_confidence * view.visible_fraction, area));
}

void CameraDetector::add_false_balls(const WorldSnapshot& world, vision_frame_t& frame) {
  if (false_ball_probability_ <= 0) return;
  for (const WorldSnapshot::Robot& robot : world.robots) {
    if (!sees(Eigen::Vector3d(robot.position.x(), robot.position.y(), robot.size.height))) {
      continue;
    }
    if (!random_.chance(false_ball_probability_)) continue;
    // Real systems see spurious orange blobs at the dribbler bar, just in front of the robot.
    const double reach = robot.size.front_distance + world.ball_radius;
    const Eigen::Vector3d spot(robot.position.x() + reach * std::cos(robot.orientation) +
                                   random_.gaussian(profile_.false_ball_spread),
                               robot.position.y() + reach * std::sin(robot.orientation) +
                                   random_.gaussian(profile_.false_ball_spread),
                               world.ball_radius);
    if (const auto seen = locate(spot, world.ball_radius)) {
      // As ER-Force's false balls: a whole ball's area, no area noise.
      frame.balls.push_back(make_ball(*seen + object_offset_, world.ball_radius,
                                      profile_.false_ball_confidence,
                                      ball_area(spot, world.ball_radius)));
    }
  }
}

vision_frame_t CameraDetector::capture(const WorldSnapshot& world, std::int64_t frame_number) {
  vision_frame_t frame{};
  frame.camera_id = id_;
  frame.frame_number = frame_number;
  frame.t_capture = world.sim_time;
  frame.t_sent = world.sim_time + processing_time_;
  for (const WorldSnapshot::Robot& robot : world.robots) detect_robot(robot, frame);
  detect_ball(world, frame);
  add_false_balls(world, frame);
  // As a real vision server lists them: the most confident ball first.
  std::stable_sort(
      frame.balls.begin(), frame.balls.end(),
      [](const vision_ball_t& a, const vision_ball_t& b) { return a.confidence > b.confidence; });
  frame.num_balls = static_cast<std::int32_t>(frame.balls.size());
  frame.num_robots_yellow = static_cast<std::int32_t>(frame.robots_yellow.size());
  frame.num_robots_blue = static_cast<std::int32_t>(frame.robots_blue.size());
  return frame;
}

}  // namespace ubersim::vision
