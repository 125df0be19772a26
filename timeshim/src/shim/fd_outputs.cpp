// Calls that can end another thread's wait for an fd without being a write
// the kernel counts (/proc/<tid>/io's syscw counts write, writev, pwrite and
// the like, also libc's own): counted in the segment before they run
// (Header::fd_outputs), so that in deterministic mode the controller knows
// when a turn can have woken a thread that waits for input (light_look.cpp).
// send, sendto, sendmsg and close count in socket_timeouts.cpp, where they
// are interposed already.
#include <stdio.h>
#include <sys/socket.h>
#include <unistd.h>

#include "runtime.hpp"

namespace shim = ubersim::timeshim::shim;

extern "C" {

__attribute__((visibility("default"))) int sendmmsg(int fd, mmsghdr* messages, unsigned int count,
                                                    int flags) {
  static const auto next = shim::next_symbol<int (*)(int, mmsghdr*, unsigned int, int)>("sendmmsg");
  shim::note_fd_output();
  return next(fd, messages, count, flags);
}

// A connection wakes the listener's accept (or its poll).
__attribute__((visibility("default"))) int connect(int fd, const sockaddr* address,
                                                   socklen_t length) {
  static const auto next = shim::next_symbol<int (*)(int, const sockaddr*, socklen_t)>("connect");
  shim::note_fd_output();
  return next(fd, address, length);
}

// A shutdown, or a close of the last descriptor of a socket or pipe, wakes
// the peer's reader with an end of file.
__attribute__((visibility("default"))) int shutdown(int fd, int how) {
  static const auto next = shim::next_symbol<int (*)(int, int)>("shutdown");
  shim::note_fd_output();
  return next(fd, how);
}

__attribute__((visibility("default"))) int dup2(int from, int to) {
  static const auto next = shim::next_symbol<int (*)(int, int)>("dup2");
  shim::note_fd_output();  // closes `to`
  return next(from, to);
}

__attribute__((visibility("default"))) int dup3(int from, int to, int flags) {
  static const auto next = shim::next_symbol<int (*)(int, int, int)>("dup3");
  shim::note_fd_output();
  return next(from, to, flags);
}

// libc closes a stream's descriptor with its own close, which the shim's
// does not see.
__attribute__((visibility("default"))) int fclose(FILE* stream) {
  static const auto next = shim::next_symbol<int (*)(FILE*)>("fclose");
  shim::note_fd_output();
  return next(stream);
}

}  // extern "C"
