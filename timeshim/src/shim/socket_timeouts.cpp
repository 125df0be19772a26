// Socket timeouts (SO_RCVTIMEO, SO_SNDTIMEO; docs/timeshim.md, "What it
// intercepts"): the shim keeps the timeout, gives the kernel none, and a
// blocking receive, accept or send on such a socket waits for readiness or
// the sim deadline. In deterministic mode a blocking receive hands the run
// token over while it waits.
#include <fcntl.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>

#include "det_sync.hpp"
#include "fd_waits.hpp"
#include "runtime.hpp"
#include "timers.hpp"

namespace shim = ubersim::timeshim::shim;
using ubersim::timeshim::ShimCall;

namespace {

// Receive and send timeouts in ns by fd (0: none).
using shim::kMaxFd;
std::atomic<std::int64_t> receive_timeout_ns[kMaxFd];
std::atomic<std::int64_t> send_timeout_ns[kMaxFd];

// SO_RCVTIMEO_NEW and SO_SNDTIMEO_NEW have the layout of timeval on 64-bit Linux.
constexpr int kReceiveTimeoutNew = 66;
constexpr int kSendTimeoutNew = 67;

// The table an option's timeout goes to, or nullptr for other options.
std::atomic<std::int64_t>* timeout_table(int level, int option) {
  if (level != SOL_SOCKET) return nullptr;
  if (option == SO_RCVTIMEO || option == kReceiveTimeoutNew) return receive_timeout_ns;
  if (option == SO_SNDTIMEO || option == kSendTimeoutNew) return send_timeout_ns;
  return nullptr;
}

std::int64_t timeout_in(const std::atomic<std::int64_t>* table, int fd) {
  // Set only while the shim is active (setsockopt); no segment() here, as
  // read() may come while the shim attaches.
  if (fd < 0 || fd >= kMaxFd) return 0;
  return table[fd].load(std::memory_order_relaxed);
}
std::int64_t timeout_of(int fd) {
  return timeout_in(receive_timeout_ns, fd);
}

bool blocking(int fd, int flags) {
  return (flags & MSG_DONTWAIT) == 0 && (::fcntl(fd, F_GETFL) & O_NONBLOCK) == 0;
}

// Tries `receive` without blocking; while nothing is there, waits for data
// until the socket's sim-time timeout, then fails with EAGAIN as the kernel
// would have.
template <typename Receive>
ssize_t receive_until(int fd, std::int64_t timeout, Receive&& receive, short events = POLLIN,
                      ShimCall call = ShimCall::SocketReceive) {
  const std::int64_t deadline = shim::deadline_after(shim::view_now(), timeout);
  for (;;) {
    const ssize_t got = receive(MSG_DONTWAIT);
    if (got >= 0 || (errno != EAGAIN && errno != EWOULDBLOCK)) return got;
    pollfd wanted{fd, events, 0};
    const int ready = shim::poll_until(&wanted, 1, deadline, nullptr, call);
    if (ready < 0) return -1;
    if (ready == 0) {
      errno = EAGAIN;
      return -1;
    }
  }
}

}  // namespace

extern "C" {

__attribute__((visibility("default"))) int setsockopt(int fd, int level, int option,
                                                      const void* value,
                                                      socklen_t length) noexcept {
  static const auto next =
      shim::next_symbol<int (*)(int, int, int, const void*, socklen_t)>("setsockopt");
  std::atomic<std::int64_t>* table = timeout_table(level, option);
  if (table == nullptr || fd < 0 || fd >= kMaxFd || shim::segment() == nullptr ||
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
    table[fd].store(static_cast<std::int64_t>(timeout->tv_sec) * shim::kNsPerSecond +
                    static_cast<std::int64_t>(timeout->tv_usec) * 1000);
  }
  return result;
}

__attribute__((visibility("default"))) int getsockopt(int fd, int level, int option, void* value,
                                                      socklen_t* length) noexcept {
  static const auto next =
      shim::next_symbol<int (*)(int, int, int, void*, socklen_t*)>("getsockopt");
  const std::atomic<std::int64_t>* table = timeout_table(level, option);
  const std::int64_t timeout = table == nullptr ? 0 : timeout_in(table, fd);
  if (timeout == 0 || *length < static_cast<socklen_t>(sizeof(timeval))) {
    return next(fd, level, option, value, length);
  }
  auto* result = static_cast<timeval*>(value);
  result->tv_sec = static_cast<time_t>(timeout / shim::kNsPerSecond);
  result->tv_usec = static_cast<suseconds_t>((timeout % shim::kNsPerSecond) / 1000);
  *length = sizeof(timeval);
  return 0;
}

__attribute__((visibility("default"))) ssize_t recv(int fd, void* buffer, size_t size, int flags) {
  static const auto next = shim::next_symbol<ssize_t (*)(int, void*, size_t, int)>("recv");
  const std::int64_t timeout = timeout_of(fd);
  if (timeout == 0 || !blocking(fd, flags)) {
    shim::det_await_fd(fd, POLLIN, flags);
    return next(fd, buffer, size, flags);
  }
  return receive_until(fd, timeout, [&](int more) { return next(fd, buffer, size, flags | more); });
}

__attribute__((visibility("default"))) ssize_t recvfrom(int fd, void* buffer, size_t size,
                                                        int flags, sockaddr* from,
                                                        socklen_t* from_length) {
  static const auto next =
      shim::next_symbol<ssize_t (*)(int, void*, size_t, int, sockaddr*, socklen_t*)>("recvfrom");
  const std::int64_t timeout = timeout_of(fd);
  if (timeout == 0 || !blocking(fd, flags)) {
    shim::det_await_fd(fd, POLLIN, flags);
    return next(fd, buffer, size, flags, from, from_length);
  }
  return receive_until(fd, timeout, [&](int more) {
    return next(fd, buffer, size, flags | more, from, from_length);
  });
}

__attribute__((visibility("default"))) ssize_t recvmsg(int fd, msghdr* message, int flags) {
  static const auto next = shim::next_symbol<ssize_t (*)(int, msghdr*, int)>("recvmsg");
  const std::int64_t timeout = timeout_of(fd);
  if (timeout == 0 || !blocking(fd, flags)) {
    shim::det_await_fd(fd, POLLIN, flags);
    return next(fd, message, flags);
  }
  return receive_until(fd, timeout, [&](int more) { return next(fd, message, flags | more); });
}

__attribute__((visibility("default"))) ssize_t read(int fd, void* buffer, size_t size) {
  static const auto next = shim::next_symbol<ssize_t (*)(int, void*, size_t)>("read");
  const std::int64_t timeout = timeout_of(fd);
  if (timeout == 0 || !blocking(fd, 0)) {
    shim::det_await_fd(fd, POLLIN, 0);
    return next(fd, buffer, size);
  }
  static const auto next_recv = shim::next_symbol<ssize_t (*)(int, void*, size_t, int)>("recv");
  return receive_until(fd, timeout, [&](int more) { return next_recv(fd, buffer, size, more); });
}

__attribute__((visibility("default"))) int accept4(int fd, sockaddr* address, socklen_t* length,
                                                   int flags) {
  static const auto next = shim::next_symbol<int (*)(int, sockaddr*, socklen_t*, int)>("accept4");
  const std::int64_t timeout = timeout_of(fd);
  if (timeout == 0 || !blocking(fd, 0)) {
    shim::det_await_fd(fd, POLLIN, 0);
    return next(fd, address, length, flags);
  }
  // The listening socket is blocking: wait for a connection until the sim
  // deadline, then take it (nobody else of the group does meanwhile).
  pollfd wanted{fd, POLLIN, 0};
  const int ready = shim::poll_until(&wanted, 1, shim::deadline_after(shim::view_now(), timeout),
                                     nullptr, ShimCall::Accept);
  if (ready < 0) return -1;
  if (ready == 0) {
    errno = EAGAIN;
    return -1;
  }
  return next(fd, address, length, flags);
}

__attribute__((visibility("default"))) int accept(int fd, sockaddr* address, socklen_t* length) {
  return accept4(fd, address, length, 0);
}

__attribute__((visibility("default"))) ssize_t send(int fd, const void* buffer, size_t size,
                                                    int flags) {
  static const auto next = shim::next_symbol<ssize_t (*)(int, const void*, size_t, int)>("send");
  shim::note_fd_output();
  const std::int64_t timeout = timeout_in(send_timeout_ns, fd);
  if (timeout == 0 || !blocking(fd, flags)) return next(fd, buffer, size, flags);
  return receive_until(
      fd, timeout, [&](int more) { return next(fd, buffer, size, flags | more); }, POLLOUT,
      ShimCall::SocketSend);
}

__attribute__((visibility("default"))) ssize_t sendto(int fd, const void* buffer, size_t size,
                                                      int flags, const sockaddr* to,
                                                      socklen_t to_length) {
  static const auto next =
      shim::next_symbol<ssize_t (*)(int, const void*, size_t, int, const sockaddr*, socklen_t)>(
          "sendto");
  shim::note_fd_output();
  const std::int64_t timeout = timeout_in(send_timeout_ns, fd);
  if (timeout == 0 || !blocking(fd, flags)) return next(fd, buffer, size, flags, to, to_length);
  return receive_until(
      fd, timeout, [&](int more) { return next(fd, buffer, size, flags | more, to, to_length); },
      POLLOUT, ShimCall::SocketSend);
}

__attribute__((visibility("default"))) ssize_t sendmsg(int fd, const msghdr* message, int flags) {
  static const auto next = shim::next_symbol<ssize_t (*)(int, const msghdr*, int)>("sendmsg");
  shim::note_fd_output();
  const std::int64_t timeout = timeout_in(send_timeout_ns, fd);
  if (timeout == 0 || !blocking(fd, flags)) return next(fd, message, flags);
  return receive_until(
      fd, timeout, [&](int more) { return next(fd, message, flags | more); }, POLLOUT,
      ShimCall::SocketSend);
}

__attribute__((visibility("default"))) ssize_t write(int fd, const void* buffer, size_t size) {
  static const auto next = shim::next_symbol<ssize_t (*)(int, const void*, size_t)>("write");
  const std::int64_t timeout = timeout_in(send_timeout_ns, fd);
  if (timeout == 0 || !blocking(fd, 0)) return next(fd, buffer, size);
  static const auto next_send =
      shim::next_symbol<ssize_t (*)(int, const void*, size_t, int)>("send");
  return receive_until(
      fd, timeout, [&](int more) { return next_send(fd, buffer, size, more); }, POLLOUT,
      ShimCall::SocketSend);
}

__attribute__((visibility("default"))) int close(int fd) {
  static const auto next = shim::next_symbol<int (*)(int)>("close");
  shim::note_fd_output();
  if (fd >= 0 && fd < kMaxFd) {
    receive_timeout_ns[fd].store(0, std::memory_order_relaxed);
    send_timeout_ns[fd].store(0, std::memory_order_relaxed);
  }
  shim::forget_timer(fd);
  return next(fd);
}

}  // extern "C"
