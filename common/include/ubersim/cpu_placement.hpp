#pragma once
// Where the simulator's processes run in real time: on one CPU, as
// tools/launch.sh places them (docs/design.md, "One core in real time"), for
// the programs that start the set themselves (the truth bench, the report's
// CPU rig) so that they measure what a user runs.
#include <sched.h>

namespace ubersim {

// The last CPU this process may run on (launch.sh's default), or -1 when
// that cannot be read.
int last_allowed_cpu();

// While it lives, the calling thread runs only on `cpu`, and so does every
// process it starts (a child inherits its parent's CPUs); restores the CPUs
// it had. A negative cpu changes nothing.
class OnOneCpu {
 public:
  explicit OnOneCpu(int cpu);
  ~OnOneCpu();
  OnOneCpu(const OnOneCpu&) = delete;
  OnOneCpu& operator=(const OnOneCpu&) = delete;

 private:
  cpu_set_t before_{};
  bool changed_ = false;
};

}  // namespace ubersim
