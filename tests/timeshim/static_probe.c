/* A statically linked program (LD_PRELOAD has no effect on it), for the time
   shim's tests: sleeps one second of wall time. */
#include <time.h>

int main(void) {
  struct timespec second = {1, 0};
  nanosleep(&second, 0);
  return 0;
}
