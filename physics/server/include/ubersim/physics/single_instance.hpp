#pragma once
// One physics per bus: a second ubersim_physics on the LCM port and channel
// prefix another one already steps on would corrupt both runs without a word
// (each world's SIM_STATE interleaved with the other's, two answers to every
// request). So the physics program claims its bus before it loads or steps
// anything, and a second one stops with one line naming the first.
//
// The claim is a listening unix socket with an abstract name built from the
// LCM port and the channel prefix (docs/physics.md, "One physics per bus"):
//   * the kernel releases it when its process ends, however it ends (a lock
//     file would outlive a crash and refuse the next start);
//   * abstract names belong to the network namespace, as LCM's multicast on
//     the loopback does: runs isolated in namespaces of their own never meet;
//   * the second start connects to it and reads the holder's pid (SO_PEERCRED).
// The port alone, not the group: LCM binds INADDR_ANY:port, and Linux hands
// such a socket every group joined on that port on the host, so two groups on
// one port share their traffic.
#include <sys/types.h>

#include <optional>
#include <stdexcept>
#include <string>

namespace ubersim::physics {

// The abstract socket name (without its leading NUL) of the bus that LCM URL
// and channel prefix make, or nothing for a URL that is not udpm:// (memq://
// stays in its process: nothing to share).
std::optional<std::string> bus_claim_name(const std::string& lcm_url,
                                          const std::string& channel_prefix);

// Thrown when another process holds the claim; what() is the one line a user
// reads: who holds it and how to run beside it.
class BusTaken : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The claim, held for the object's lifetime.
class BusClaim {
 public:
  // Claims the bus of lcm_url and channel_prefix. Throws BusTaken if another
  // process holds it, std::runtime_error if the socket cannot be made.
  static BusClaim claim(const std::string& lcm_url, const std::string& channel_prefix);
  // Throws BusTaken if another process holds that claim, without claiming it: a
  // check (--check-bus) that ran beside a starting physics must never take its bus.
  static void check(const std::string& lcm_url, const std::string& channel_prefix);

  BusClaim(BusClaim&& other) noexcept;
  BusClaim& operator=(BusClaim&& other) noexcept;
  BusClaim(const BusClaim&) = delete;
  BusClaim& operator=(const BusClaim&) = delete;
  ~BusClaim();

  bool held() const { return fd_ >= 0; }

 private:
  explicit BusClaim(int fd) : fd_(fd) {}
  int fd_ = -1;
};

// The pid of the process that holds the claim of that name, if one does and
// it answers (nothing if none does or its queue is full).
std::optional<pid_t> bus_claim_holder(const std::string& name);

}  // namespace ubersim::physics
