#include "ubersim/physics/ode_handles.hpp"

#include <cstdarg>
#include <cstdio>
#include <mutex>

#include "ubersim/spdlog.hpp"

namespace ubersim::physics {
namespace {

std::string format_ode_message(const char* format, va_list args) {
  char text[512];
  std::vsnprintf(text, sizeof text, format, args);
  return text;
}

// ODE reports through printf-style handlers; route them into our log.
void on_ode_message(int number, const char* format, va_list args) {
  spdlog::debug("ODE message {}: {}", number, format_ode_message(format, args));
}
void on_ode_error(int number, const char* format, va_list args) {
  spdlog::error("ODE error {}: {}", number, format_ode_message(format, args));
}

struct OdeLibrary {
  OdeLibrary() {
    dInitODE2(0);
    dSetMessageHandler(on_ode_message);
    dSetDebugHandler(on_ode_error);
    dSetErrorHandler(on_ode_error);
  }
  ~OdeLibrary() { dCloseODE(); }
};

}  // namespace

void ensure_ode_initialised() {
  static OdeLibrary library;
  // Collision needs per-thread data; allocating again is a cheap no-op.
  thread_local bool thread_ready = false;
  if (!thread_ready) {
    dAllocateODEDataForThread(dAllocateMaskAll);
    thread_ready = true;
  }
}

SpaceHandle make_simple_space(dSpaceID parent) {
  SpaceHandle space(dSimpleSpaceCreate(parent));
  dSpaceSetCleanup(space.get(), 0);
  return space;
}

}  // namespace ubersim::physics
