#pragma once
// The tests use the shared ChildProcess (common/) under their own namespace.
#include "ubersim/child_process.hpp"

namespace ubersim::test {
using ubersim::ChildProcess;
using ubersim::process_alive;
}  // namespace ubersim::test
