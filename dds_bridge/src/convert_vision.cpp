#include "ubersim/dds_bridge/convert_vision.hpp"

namespace ubersim::dds {
namespace {

void ball_to_dds(const vision_ball_t& from, DdsVisionBall& to) {
  to.confidence = from.confidence;
  to.x = from.x;
  to.y = from.y;
  to.pixel_x = from.pixel_x;
  to.pixel_y = from.pixel_y;
  to.area = from.area;
}

vision_ball_t ball_from_dds(const DdsVisionBall& from) {
  vision_ball_t to{};
  to.confidence = from.confidence;
  to.x = from.x;
  to.y = from.y;
  to.pixel_x = from.pixel_x;
  to.pixel_y = from.pixel_y;
  to.area = from.area;
  return to;
}

void robot_to_dds(const vision_robot_t& from, DdsVisionRobot& to) {
  to.robot_id = from.robot_id;
  to.confidence = from.confidence;
  to.x = from.x;
  to.y = from.y;
  to.orientation = from.orientation;
  to.pixel_x = from.pixel_x;
  to.pixel_y = from.pixel_y;
}

vision_robot_t robot_from_dds(const DdsVisionRobot& from) {
  vision_robot_t to{};
  to.robot_id = from.robot_id;
  to.confidence = from.confidence;
  to.x = from.x;
  to.y = from.y;
  to.orientation = from.orientation;
  to.pixel_x = from.pixel_x;
  to.pixel_y = from.pixel_y;
  return to;
}

}  // namespace

OwnedSample<DdsVisionFrame> to_dds(const vision_frame_t& frame) {
  OwnedSample<DdsVisionFrame> sample;
  DdsVisionFrame& to = sample.get();
  to.camera_id = frame.camera_id;
  to.frame_number = frame.frame_number;
  to.t_capture = frame.t_capture;
  to.t_sent = frame.t_sent;
  fill_sequence(to.balls, frame.balls, ball_to_dds);
  fill_sequence(to.robots_yellow, frame.robots_yellow, robot_to_dds);
  fill_sequence(to.robots_blue, frame.robots_blue, robot_to_dds);
  return sample;
}

vision_frame_t from_dds(const DdsVisionFrame& frame) {
  vision_frame_t to{};
  to.camera_id = frame.camera_id;
  to.frame_number = frame.frame_number;
  to.t_capture = frame.t_capture;
  to.t_sent = frame.t_sent;
  to.balls = from_dds_sequence<vision_ball_t>(frame.balls, ball_from_dds);
  to.num_balls = count_of(to.balls);
  to.robots_yellow = from_dds_sequence<vision_robot_t>(frame.robots_yellow, robot_from_dds);
  to.num_robots_yellow = count_of(to.robots_yellow);
  to.robots_blue = from_dds_sequence<vision_robot_t>(frame.robots_blue, robot_from_dds);
  to.num_robots_blue = count_of(to.robots_blue);
  return to;
}

}  // namespace ubersim::dds
