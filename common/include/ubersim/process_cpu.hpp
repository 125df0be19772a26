#pragma once
// CPU time of another process, for the benchmarks and the report.
#include <sys/types.h>

namespace ubersim {

// Seconds the process's threads have spent on a CPU, in nanoseconds' resolution
// (/proc/<pid>/task/<tid>/schedstat): /proc/<pid>/stat counts 10 ms ticks, too
// coarse for windows of a few seconds of a process using 1 % of a core. Falls
// back to /proc/<pid>/stat's utime + stime when schedstat is not there.
double process_cpu_seconds(pid_t pid);

}  // namespace ubersim
