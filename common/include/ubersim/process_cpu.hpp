#pragma once
// CPU time of another process, for the benchmarks and the report, and of the
// calling thread.
#include <sys/types.h>

#include <optional>

namespace ubersim {

// User (utime) and kernel (stime) time of a process in seconds, fields 14 and
// 15 of /proc/<pid>/stat, in 10 ms ticks; nothing when it cannot be read.
struct ProcessStatTimes {
  double user = 0, system = 0;
};
std::optional<ProcessStatTimes> process_stat_times(pid_t pid);

// Seconds the process's threads have spent on a CPU, in nanoseconds' resolution
// (/proc/<pid>/task/<tid>/schedstat): /proc/<pid>/stat counts 10 ms ticks, too
// coarse for windows of a few seconds of a process using 1 % of a core. Falls
// back to /proc/<pid>/stat's utime + stime when schedstat is not there.
double process_cpu_seconds(pid_t pid);

// Seconds the calling thread has spent on a CPU (CLOCK_THREAD_CPUTIME_ID: a
// system call, there is no vDSO for it).
double thread_cpu_seconds();

}  // namespace ubersim
