#pragma once
// What a team program under the time shim sent that changes the field (a
// simulation control command, a grSim replacement) waits for the next vision
// frame and goes to physics with it: physics waits at that frame's state and
// applies it there, on every run (docs/timeshim.md, "Integration with sync
// mode"). Sent at once, it would apply at whatever step physics had reached
// in wall time. Held in arrival order, at most kMost of them: a bound against
// a flood, beyond which the caller applies at once.
#include <cstddef>
#include <utility>
#include <vector>

namespace ubersim::ssl {

template <typename Item>
class HeldForNextFrame {
 public:
  static constexpr std::size_t kMost = 256;

  // False when full: the caller applies `item` now instead.
  bool hold(Item item) {
    if (items_.size() >= kMost) return false;
    items_.push_back(std::move(item));
    return true;
  }
  // Applies every held item, oldest first, and forgets them.
  template <typename Apply>
  void release(Apply&& apply) {
    std::vector<Item> due;
    due.swap(items_);
    for (const Item& item : due) apply(item);
  }

 private:
  std::vector<Item> items_;
};

}  // namespace ubersim::ssl
