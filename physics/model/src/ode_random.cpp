// ODE's random generator, one per thread (docs/python.md, "Threads").
//
// ODE 0.16's QuickStep reorders constraints with dRandInt(), which draws from
// a single process-wide seed. World::step() hands that seed its own state
// before each solve and takes it back after (world.cpp), so worlds stepped one
// after another never disturb each other. Worlds stepped at the same time on
// several threads (the Python VectorSim) would race on that one seed and lose
// determinism. These definitions take the place of libode's (its own calls go
// through the PLT, so a definition in the program or in the module that loads
// libode wins) and keep the seed per thread. The generator is the same as
// libode's (seed = 1664525 seed + 1013904223 mod 2^32), so a single-threaded
// run draws exactly the numbers it drew before.
#include <ode/ode.h>

#include <cstdint>

namespace {
thread_local std::uint32_t ode_seed = 0;
}  // namespace

extern "C" {

__attribute__((visibility("default"))) unsigned long dRand() {
  ode_seed = ode_seed * 1664525u + 1013904223u;
  return ode_seed;
}

__attribute__((visibility("default"))) unsigned long dRandGetSeed() {
  return ode_seed;
}

__attribute__((visibility("default"))) void dRandSetSeed(unsigned long seed) {
  ode_seed = static_cast<std::uint32_t>(seed);
}

}  // extern "C"
