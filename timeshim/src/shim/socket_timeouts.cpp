// Socket receive timeouts (SO_RCVTIMEO; docs/timeshim.md, "What it
// intercepts"): the shim keeps the timeout, gives the kernel none, and a
// blocking receive on such a socket waits for data or the sim deadline.
#include <fcntl.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>

#include "fd_waits.hpp"
#include "runtime.hpp"
#include "timers.hpp"

namespace shim = ubersim::timeshim::shim;
using ubersim::timeshim::ShimCall;

namespace {

// Receive timeouts in ns by fd (0: none). Sockets with higher fds keep the
// kernel's (wall-time) timeout.
constexpr int kMaxFd = 65536;
std::atomic<std::int64_t> receive_timeout_ns[kMaxFd];

// SO_RCVTIMEO_NEW has the same layout as timeval on 64-bit Linux.
constexpr int kReceiveTimeoutNew = 66;

bool is_receive_timeout(int level, int option) {
  return level == SOL_SOCKET && (option == SO_RCVTIMEO || option == kReceiveTimeoutNew);
}

std::int64_t timeout_of(int fd) {
  // Set only while the shim is active (setsockopt); no segment() here, as
  // read() may come while the shim attaches.
  if (fd < 0 || fd >= kMaxFd) return 0;
  return receive_timeout_ns[fd].load(std::memory_order_relaxed);
}

bool blocking(int fd, int flags) {
  return (flags & MSG_DONTWAIT) == 0 && (::fcntl(fd, F_GETFL) & O_NONBLOCK) == 0;
}

// Tries `receive` without blocking; while nothing is there, waits for data
// until the socket's sim-time timeout, then fails with EAGAIN as the kernel
// would have.
template <typename Receive>
ssize_t receive_until(int fd, std::int64_t timeout, Receive&& receive) {
  const std::int64_t deadline = shim::deadline_after(shim::view_now(), timeout);
  for (;;) {
    const ssize_t got = receive(MSG_DONTWAIT);
    if (got >= 0 || (errno != EAGAIN && errno != EWOULDBLOCK)) return got;
    pollfd wanted{fd, POLLIN, 0};
    const int ready = shim::poll_until(&wanted, 1, deadline, nullptr, ShimCall::SocketReceive);
    if (ready < 0) return -1;
    if (ready == 0) {
      errno = EAGAIN;
      return -1;
    }
  }
}

template <typename Fn>
Fn real(const char* name) {
  return shim::next_symbol<Fn>(name);
}

}  // namespace

extern "C" {

__attribute__((visibility("default"))) int setsockopt(int fd, int level, int option,
                                                      const void* value,
                                                      socklen_t length) noexcept {
  static const auto next = real<int (*)(int, int, int, const void*, socklen_t)>("setsockopt");
  if (!is_receive_timeout(level, option) || fd < 0 || fd >= kMaxFd || shim::segment() == nullptr ||
      length < static_cast<socklen_t>(sizeof(timeval))) {
    return next(fd, level, option, value, length);
  }
  const auto* timeout = static_cast<const timeval*>(value);
  if (timeout->tv_usec < 0 || timeout->tv_usec >= 1000000) {
    errno = EDOM;
    return -1;
  }
  // The kernel gets no timeout: it would end the receive in wall time.
  const timeval none{0, 0};
  const int result = next(fd, level, option, &none, sizeof(none));
  if (result == 0) {
    receive_timeout_ns[fd].store(static_cast<std::int64_t>(timeout->tv_sec) * shim::kNsPerSecond +
                                 static_cast<std::int64_t>(timeout->tv_usec) * 1000);
  }
  return result;
}

__attribute__((visibility("default"))) int getsockopt(int fd, int level, int option, void* value,
                                                      socklen_t* length) noexcept {
  static const auto next = real<int (*)(int, int, int, void*, socklen_t*)>("getsockopt");
  const std::int64_t timeout = timeout_of(fd);
  if (!is_receive_timeout(level, option) || timeout == 0 ||
      *length < static_cast<socklen_t>(sizeof(timeval))) {
    return next(fd, level, option, value, length);
  }
  auto* result = static_cast<timeval*>(value);
  result->tv_sec = static_cast<time_t>(timeout / shim::kNsPerSecond);
  result->tv_usec = static_cast<suseconds_t>((timeout % shim::kNsPerSecond) / 1000);
  *length = sizeof(timeval);
  return 0;
}

__attribute__((visibility("default"))) ssize_t recv(int fd, void* buffer, size_t size, int flags) {
  static const auto next = real<ssize_t (*)(int, void*, size_t, int)>("recv");
  const std::int64_t timeout = timeout_of(fd);
  if (timeout == 0 || !blocking(fd, flags)) return next(fd, buffer, size, flags);
  return receive_until(fd, timeout, [&](int more) { return next(fd, buffer, size, flags | more); });
}

__attribute__((visibility("default"))) ssize_t recvfrom(int fd, void* buffer, size_t size,
                                                        int flags, sockaddr* from,
                                                        socklen_t* from_length) {
  static const auto next =
      real<ssize_t (*)(int, void*, size_t, int, sockaddr*, socklen_t*)>("recvfrom");
  const std::int64_t timeout = timeout_of(fd);
  if (timeout == 0 || !blocking(fd, flags)) {
    return next(fd, buffer, size, flags, from, from_length);
  }
  return receive_until(fd, timeout, [&](int more) {
    return next(fd, buffer, size, flags | more, from, from_length);
  });
}

__attribute__((visibility("default"))) ssize_t recvmsg(int fd, msghdr* message, int flags) {
  static const auto next = real<ssize_t (*)(int, msghdr*, int)>("recvmsg");
  const std::int64_t timeout = timeout_of(fd);
  if (timeout == 0 || !blocking(fd, flags)) return next(fd, message, flags);
  return receive_until(fd, timeout, [&](int more) { return next(fd, message, flags | more); });
}

__attribute__((visibility("default"))) ssize_t read(int fd, void* buffer, size_t size) {
  static const auto next = real<ssize_t (*)(int, void*, size_t)>("read");
  const std::int64_t timeout = timeout_of(fd);
  if (timeout == 0 || !blocking(fd, 0)) return next(fd, buffer, size);
  static const auto next_recv = real<ssize_t (*)(int, void*, size_t, int)>("recv");
  return receive_until(fd, timeout, [&](int more) { return next_recv(fd, buffer, size, more); });
}

__attribute__((visibility("default"))) int close(int fd) {
  static const auto next = real<int (*)(int)>("close");
  if (fd >= 0 && fd < kMaxFd) receive_timeout_ns[fd].store(0, std::memory_order_relaxed);
  shim::forget_timer(fd);
  return next(fd);
}

}  // extern "C"
