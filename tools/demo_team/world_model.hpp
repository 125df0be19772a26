#pragma once
// What a control program knows: the latest detection of each robot and of the
// ball, merged over all cameras, from VISION frames only (exactly what it has
// on the real field).
#include <map>
#include <optional>
#include <ubersim/vision_frame_t.hpp>

namespace demo {

struct Pose {
  double x = 0, y = 0, orientation = 0;  // m, m, rad
  double seen_at = -1;                   // t_capture of the frame (s)
};

struct Ball {
  double x = 0, y = 0;  // m
  double seen_at = -1;  // s
};

class WorldModel {
 public:
  // own_team_yellow: whose robots are "ours".
  explicit WorldModel(bool own_team_yellow) : yellow_(own_team_yellow) {}

  void update(const ubersim::vision_frame_t& frame);

  const std::map<int, Pose>& own() const { return own_; }
  const std::map<int, Pose>& opponents() const { return opponents_; }
  const std::optional<Ball>& ball() const { return ball_; }
  double now() const { return now_; }  // newest capture time seen (s)

  // Forgets robots not seen for `age` seconds (taken off the field, or hidden).
  void forget_older_than(double age);

 private:
  bool yellow_;
  std::map<int, Pose> own_, opponents_;
  std::optional<Ball> ball_;
  double now_ = 0;
};

}  // namespace demo
