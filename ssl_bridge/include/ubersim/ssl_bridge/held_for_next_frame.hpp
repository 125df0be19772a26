#pragma once
// What a team program under the time shim sent that changes the field (a
// simulation control command, a grSim replacement) waits for the next vision
// frame and goes to physics with it: physics waits at that frame's state and
// applies it there, on every run (docs/timeshim.md, "Integration with sync
// mode"). Sent at once, it would apply at whatever step physics had reached
// in wall time. Held with its sender, at most kMost of them: a bound against
// a flood, beyond which the caller applies at once.
//
// Released in the order of the programs that sent them, each program's in
// the order it sent them: two programs run side by side (each its own group),
// so the order in which their datagrams met in one socket is the kernel's,
// and two commands that move the same ball must apply alike on every run.
#include <netinet/in.h>

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

namespace ubersim::ssl {

template <typename Item>
class HeldForNextFrame {
 public:
  static constexpr std::size_t kMost = 256;

  // False when full: the caller applies `item` now instead.
  bool hold(Item item, const sockaddr_in& from) {
    if (held_.size() >= kMost) return false;
    held_.push_back({std::move(item), from});
    return true;
  }
  // Applies every held item (apply(item, from)), by program_of(from), then
  // oldest first, and forgets them.
  template <typename ProgramOf, typename Apply>
  void release(ProgramOf&& program_of, Apply&& apply) {
    std::vector<Held> due;
    due.swap(held_);
    std::vector<std::pair<std::size_t, std::size_t>> order;  // program, arrival
    for (std::size_t i = 0; i < due.size(); ++i) order.emplace_back(program_of(due[i].from), i);
    std::sort(order.begin(), order.end());
    for (const auto& [program, index] : order) apply(due[index].item, due[index].from);
  }

 private:
  struct Held {
    Item item;
    sockaddr_in from;
  };
  std::vector<Held> held_;
};

}  // namespace ubersim::ssl
