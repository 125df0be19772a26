#include "ubersim/cpu_placement.hpp"

namespace ubersim {

int last_allowed_cpu() {
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  if (::sched_getaffinity(0, sizeof allowed, &allowed) != 0) return -1;
  for (int cpu = CPU_SETSIZE - 1; cpu >= 0; --cpu) {
    if (CPU_ISSET(cpu, &allowed)) return cpu;
  }
  return -1;
}

OnOneCpu::OnOneCpu(int cpu) {
  CPU_ZERO(&before_);
  if (cpu < 0 || cpu >= CPU_SETSIZE || ::sched_getaffinity(0, sizeof before_, &before_) != 0) {
    return;
  }
  cpu_set_t one;
  CPU_ZERO(&one);
  CPU_SET(cpu, &one);
  changed_ = ::sched_setaffinity(0, sizeof one, &one) == 0;
}

OnOneCpu::~OnOneCpu() {
  if (changed_) ::sched_setaffinity(0, sizeof before_, &before_);
}

}  // namespace ubersim
