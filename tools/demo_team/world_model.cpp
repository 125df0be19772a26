#include "world_model.hpp"

namespace demo {
namespace {

void merge(std::map<int, Pose>& poses, const std::vector<ubersim::vision_robot_t>& detections,
           double t_capture) {
  for (const auto& d : detections) {
    Pose& pose = poses[d.robot_id];
    if (t_capture < pose.seen_at) continue;  // another camera already gave a newer view
    pose = Pose{d.x, d.y, d.orientation, t_capture};
  }
}

}  // namespace

void WorldModel::update(const ubersim::vision_frame_t& frame) {
  if (frame.t_capture > now_) now_ = frame.t_capture;
  merge(own_, yellow_ ? frame.robots_yellow : frame.robots_blue, frame.t_capture);
  merge(opponents_, yellow_ ? frame.robots_blue : frame.robots_yellow, frame.t_capture);
  // The most confident ball of the frame, if newer than what we have.
  const ubersim::vision_ball_t* best = nullptr;
  for (const auto& b : frame.balls) {
    if (best == nullptr || b.confidence > best->confidence) best = &b;
  }
  if (best != nullptr && (!ball_ || frame.t_capture >= ball_->seen_at)) {
    ball_ = Ball{best->x, best->y, frame.t_capture};
  }
}

void WorldModel::forget_older_than(double age) {
  for (auto* poses : {&own_, &opponents_}) {
    for (auto it = poses->begin(); it != poses->end();) {
      it = now_ - it->second.seen_at > age ? poses->erase(it) : std::next(it);
    }
  }
}

}  // namespace demo
