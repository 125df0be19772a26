#pragma once
// timerfd on sim time (timers.cpp).

namespace ubersim::timeshim::shim {

// The fd is closed: its timer, if it is one of the shim's, goes.
void forget_timer(int fd);

}  // namespace ubersim::timeshim::shim
