#pragma once
// Resident memory of a running process (from /proc), for tests that check
// that hostile input costs a process no more than a bounded amount of memory.
#include <sys/types.h>
#include <unistd.h>

#include <fstream>
#include <string>

namespace ubersim::test {

// kB resident now; -1 when the process is gone.
inline long resident_kilobytes(pid_t pid) {
  std::ifstream statm("/proc/" + std::to_string(pid) + "/statm");
  long pages_total = 0, pages_resident = -1;
  if (!(statm >> pages_total >> pages_resident)) return -1;
  return pages_resident * (::sysconf(_SC_PAGESIZE) / 1024);
}

}  // namespace ubersim::test
