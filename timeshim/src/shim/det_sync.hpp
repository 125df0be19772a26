#pragma once
// Deterministic mode's waits in the shim (det_sync.cpp).
#include <pthread.h>
#include <semaphore.h>

#include <cstdint>

#include "ubersim/timeshim/shared_state.hpp"

namespace ubersim::timeshim::shim {

// Blocks this thread (DetBlocked, the token handed over) until a peer's
// det_wake for `address` or sim time deadline; then waits for its turn.
// Returns true when a peer ended the wait.
bool det_block(DetObject object, const void* address, bool shared, std::int64_t deadline,
               ShimCall call);
// Makes the threads blocked on `address` want the token (or only the one
// that waits longest, for a condition signal). `shared`: any thread blocked
// on a process-shared object of this kind (their addresses differ).
void det_wake(DetObject object, const void* address, bool shared, bool only_first);
// A mutex lock, condition wait and semaphore wait done in the shim, ending
// by the sim deadline (kNoDeadline: none). Results as the libc calls'.
int det_mutex_lock(pthread_mutex_t* mutex, std::int64_t deadline);
int det_cond_wait(pthread_cond_t* cond, pthread_mutex_t* mutex, std::int64_t deadline);
int det_sem_wait(sem_t* semaphore, std::int64_t deadline);
// Before a call on fd that blocks until `events`: while it would block, the
// token is handed over (no-op outside deterministic mode, or for a
// non-blocking fd or MSG_DONTWAIT in flags).
void det_await_fd(int fd, short events, int flags);
// libc's pthread_create, for the shim's own threads (never in turn).
int real_pthread_create(pthread_t* thread, const pthread_attr_t* attributes,
                        void* (*routine)(void*), void* argument);

}  // namespace ubersim::timeshim::shim
