#pragma once
// Timers on sim time: timerfd (timers.cpp), POSIX timers (posix_timers.cpp).
#include <signal.h>
#include <time.h>

#include <cstdint>

#include "ubersim/timeshim/shared_state.hpp"

namespace ubersim::timeshim::shim {

// What timer_gettime/timerfd_gettime say of a timer's slot: the time left to
// its next expiry (at least 1 ns while armed) and its interval.
itimerspec timer_setting(const ThreadSlot& slot);

// The fd is closed: its timer, if it is one of the shim's, goes.
void forget_timer(int fd);

// A POSIX timer of this process on a sim clock (event nullptr: SIGALRM with
// the id as value); nullptr when no slot is left.
timer_t create_sim_timer(clockid_t clock, const sigevent* event);
// timer_settime and timer_gettime of such a timer (-1 and EINVAL for another id).
int set_sim_timer(timer_t id, int flags, const itimerspec* value, itimerspec* old_value);
int get_sim_timer(timer_t id, itimerspec* value);
// The helper thread: the timer expired `expirations` times since it last
// fired; notify as its sigevent says.
void fire_posix_timer(ThreadSlot& slot, std::uint64_t expirations);

}  // namespace ubersim::timeshim::shim
