#pragma once
// RAII ownership of ODE objects. ODE hands out raw handles; these make every
// owner a unique_ptr, so nothing leaks when a robot is removed or the world
// is rebuilt. Destroy order matters in ODE (a world destroys its bodies and
// joints), so owners declare the world first and everything else after it.
#include <ode/ode.h>

#include <memory>

namespace ubersim::physics {

// Initialises ODE once per process (and the calling thread's collision data).
void ensure_ode_initialised();

struct ThreadingDeleter {
  void operator()(dThreadingImplementationID t) const {
    dThreadingImplementationShutdownProcessing(t);
    dThreadingFreeImplementation(t);
  }
};
struct WorldDeleter {
  void operator()(dWorldID w) const { dWorldDestroy(w); }
};
struct SpaceDeleter {
  void operator()(dSpaceID s) const { dSpaceDestroy(s); }
};
struct GeomDeleter {
  void operator()(dGeomID g) const { dGeomDestroy(g); }
};
struct BodyDeleter {
  void operator()(dBodyID b) const { dBodyDestroy(b); }
};
struct JointDeleter {
  void operator()(dJointID j) const { dJointDestroy(j); }
};
struct JointGroupDeleter {
  void operator()(dJointGroupID g) const { dJointGroupDestroy(g); }
};

using ThreadingHandle = std::unique_ptr<dxThreadingImplementation, ThreadingDeleter>;
using WorldHandle = std::unique_ptr<dxWorld, WorldDeleter>;
using SpaceHandle = std::unique_ptr<dxSpace, SpaceDeleter>;
using GeomHandle = std::unique_ptr<dxGeom, GeomDeleter>;
using BodyHandle = std::unique_ptr<dxBody, BodyDeleter>;
using JointHandle = std::unique_ptr<dxJoint, JointDeleter>;
using JointGroupHandle = std::unique_ptr<dxJointGroup, JointGroupDeleter>;

// A space that does not destroy its geoms: each geom has its own owner.
SpaceHandle make_simple_space(dSpaceID parent);

}  // namespace ubersim::physics
