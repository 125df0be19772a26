#pragma once
// The shim's wait for fd readiness until a sim deadline (fd_waits.cpp), for
// the calls built on it.
#include <poll.h>
#include <signal.h>

#include <cstdint>

#include "ubersim/timeshim/shared_state.hpp"

namespace ubersim::timeshim::shim {

// poll() until readiness or sim time reaches `deadline` (kNoDeadline: none);
// app_mask as ppoll's (nullptr: the thread's own). Returns as ppoll does (0
// when the deadline came first).
int poll_until(pollfd* fds, nfds_t count, std::int64_t deadline, const sigset_t* app_mask,
               ShimCall call);

}  // namespace ubersim::timeshim::shim
