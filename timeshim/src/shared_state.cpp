// Futex calls and call names shared by the shim and the controller.
#include "ubersim/timeshim/shared_state.hpp"

#include <linux/futex.h>
#include <sys/syscall.h>
#include <time.h>
#include <unistd.h>

namespace ubersim::timeshim {

const char* shim_call_name(ShimCall call) {
  switch (call) {
    case ShimCall::None:
      return "none";
    case ShimCall::Nanosleep:
      return "nanosleep";
    case ShimCall::ClockNanosleep:
      return "clock_nanosleep";
    case ShimCall::Usleep:
      return "usleep";
    case ShimCall::Sleep:
      return "sleep";
    case ShimCall::Select:
      return "select";
    case ShimCall::Pselect:
      return "pselect";
    case ShimCall::Poll:
      return "poll";
    case ShimCall::Ppoll:
      return "ppoll";
    case ShimCall::EpollWait:
      return "epoll_wait";
    case ShimCall::EpollPwait:
      return "epoll_pwait";
    case ShimCall::SemTimedwait:
      return "sem_timedwait";
    case ShimCall::CondTimedwait:
      return "pthread_cond_timedwait";
    case ShimCall::SocketReceive:
      return "a socket receive with SO_RCVTIMEO";
    case ShimCall::ChargedYield:
      return "charged pause (a thread that does not block)";
    case ShimCall::MutexLock:
      return "pthread_mutex_lock";
    case ShimCall::CondWait:
      return "pthread_cond_wait";
    case ShimCall::SemWait:
      return "sem_wait";
    case ShimCall::ThreadStart:
      return "its start (waiting for its first turn)";
    case ShimCall::BlockingCall:
      return "a blocking call";
    case ShimCall::SocketSend:
      return "a socket send with SO_SNDTIMEO";
    case ShimCall::Accept:
      return "accept with SO_RCVTIMEO";
    case ShimCall::SigTimedwait:
      return "sigtimedwait";
    case ShimCall::EpollPwait2:
      return "epoll_pwait2";
  }
  return "unknown";
}

long futex_wait(std::atomic<std::uint32_t>& word, std::uint32_t expected, long timeout_ns) {
  timespec timeout{};
  timespec* timeout_ptr = nullptr;
  if (timeout_ns >= 0) {
    timeout.tv_sec = timeout_ns / 1000000000L;
    timeout.tv_nsec = timeout_ns % 1000000000L;
    timeout_ptr = &timeout;
  }
  // std::atomic<uint32_t> is a plain 32-bit word (static_assert in the header).
  return ::syscall(SYS_futex, reinterpret_cast<std::uint32_t*>(&word), FUTEX_WAIT, expected,
                   timeout_ptr, nullptr, 0);
}

void futex_wake_all(std::atomic<std::uint32_t>& word) {
  ::syscall(SYS_futex, reinterpret_cast<std::uint32_t*>(&word), FUTEX_WAKE, 0x7fffffff, nullptr,
            nullptr, 0);
}

void start_turn(Header& segment, ThreadSlot& holder) {
  segment.turns.fetch_add(1);
  holder.wake_seq.fetch_add(1);
  futex_wake_all(holder.wake_seq);
}

}  // namespace ubersim::timeshim
