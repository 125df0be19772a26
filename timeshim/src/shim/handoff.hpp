#pragma once
// Deterministic mode: turns the shim hands from one thread to the next itself
// (handoff.cpp), without the controller's look between them.
#include <sys/types.h>

#include "ubersim/timeshim/shared_state.hpp"

namespace ubersim::timeshim::shim {

// This thread was given the token: what its turn must leave as it is.
// (`segment`: the shim's, passed in, as this runs while the shim starts.)
void note_turn_start(Header& segment);
// Its turn ended without hand_off_turn: what it wrote is not known any more.
void forget_turn_writes();
// At the end of a turn whose thread (`own`, `own_tid`, holding the token)
// has just said in its slot what it waits for: gives the token to the next
// thread in the queue, as the controller's next look would, and returns true;
// or returns false when only a look can tell who is next (the turn output
// to an fd, created a thread, sent a signal, or a thread is between states).
bool hand_off_turn(Header& segment, ThreadSlot& own, pid_t own_tid);

}  // namespace ubersim::timeshim::shim
