#pragma once
// What a geom is, so the contact handler can pick the surface parameters of
// a touching pair. Every geom's ODE user data points to one of these, owned
// by whoever owns the geom.
#include <ode/ode.h>

namespace ubersim::physics {

class Robot;

enum class GeomKind { Ground, Wall, Ball, Chassis, Wheel, Caster };

// Collision filtering (ODE category/collide bits): wheels and casters touch
// only the floor; walls never test against walls or the floor.
namespace collide_bits {
inline constexpr unsigned long kGround = 1u << 0;
inline constexpr unsigned long kWall = 1u << 1;
inline constexpr unsigned long kBall = 1u << 2;
inline constexpr unsigned long kChassis = 1u << 3;
inline constexpr unsigned long kWheel = 1u << 4;  // wheels and casters
}  // namespace collide_bits

// A standing wheel's static grip on the floor (jointed model, drive_jointed.cpp):
// while `active`, the wheel's floor contact takes the wheel back to `anchor`,
// the centre it had when its robot stopped.
struct WheelGrip {
  bool active = false;
  double anchor[3] = {0, 0, 0};  // m, world frame
};

struct GeomTag {
  GeomKind kind = GeomKind::Wall;
  Robot* robot = nullptr;           // chassis, wheels, casters
  dJointID wheel_hinge = nullptr;   // wheels of the jointed model: rolling direction
  const WheelGrip* grip = nullptr;  // wheels of the jointed model
};

// Sets a geom's tag and its category/collide bits for its kind.
void tag_geom(dGeomID geom, GeomTag* tag);

}  // namespace ubersim::physics
