/* A program that reads the clock without libc, as the Go runtime does
 * (test_timeshim.cpp): a raw clock_gettime system call, which LD_PRELOAD
 * cannot reach. It carries the section a Go program is recognised by; the
 * controller must name it, not let it run on wall time unnoticed. */
#include <stdio.h>
#include <sys/syscall.h>
#include <time.h>
#include <unistd.h>

__attribute__((section(".go.buildinfo"), used)) static const char go_build_info[] =
    "\xff Go buildinf:";

static double raw_monotonic_s(void) {
  struct timespec now;
  syscall(SYS_clock_gettime, CLOCK_MONOTONIC, &now);
  return (double)now.tv_sec + (double)now.tv_nsec * 1e-9;
}

int main(void) {
  const double start = raw_monotonic_s();
  const struct timespec pause = {0, 300000000};
  syscall(SYS_nanosleep, &pause, NULL);
  printf("raw_elapsed %.3f\n", raw_monotonic_s() - start); /* wall time */
  return 0;
}
