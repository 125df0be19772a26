#pragma once
// Which camera sees a point, as the ER-Force simulator decides it: every
// camera owns the part of the field nearer to it than to any other camera,
// measured in Manhattan distance on the ground (rectangular regions for
// cameras hung in a grid), and sees `overlap` metres past the border of that
// region. Between two cameras the border moves by `overlap` each way, so the
// strip both see is 2 x overlap wide. An inactive rule lets every camera see
// whatever its image shows.
#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <vector>

namespace ubersim::vision {

class CameraRegions {
 public:
  CameraRegions() = default;  // inactive
  // centres: every camera's true position on the ground, in camera order.
  CameraRegions(std::vector<Eigen::Vector2d> centres, double overlap)
      : centres_(std::move(centres)), overlap_(overlap) {}

  bool active() const { return !centres_.empty() && overlap_ >= 0; }
  double overlap() const { return overlap_; }

  // Whether camera `index` sees the ground point p (always when inactive).
  bool contains(std::size_t index, const Eigen::Vector2d& p) const {
    if (!active() || index >= centres_.size()) return true;
    double nearest = manhattan(centres_.front(), p);
    for (const Eigen::Vector2d& c : centres_) nearest = std::min(nearest, manhattan(c, p));
    return manhattan(centres_[index], p) <= nearest + 2 * overlap_;
  }

 private:
  static double manhattan(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a - b).cwiseAbs().sum();
  }

  std::vector<Eigen::Vector2d> centres_;
  double overlap_ = -1;  // m
};

}  // namespace ubersim::vision
