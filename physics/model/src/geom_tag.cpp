#include "ubersim/physics/geom_tag.hpp"

namespace ubersim::physics {

void tag_geom(dGeomID geom, GeomTag* tag) {
  using namespace collide_bits;
  dGeomSetData(geom, tag);
  unsigned long category = 0;
  unsigned long collide = 0;
  switch (tag->kind) {
    case GeomKind::Ground:
      category = kGround;
      collide = kWheel | kBall | kChassis;
      break;
    case GeomKind::Wall:
      category = kWall;
      collide = kBall | kChassis;
      break;
    case GeomKind::Ball:
      category = kBall;
      collide = kGround | kWall | kChassis;
      break;
    case GeomKind::Chassis:
      category = kChassis;
      collide = kGround | kWall | kBall | kChassis;
      break;
    case GeomKind::Wheel:
    case GeomKind::Caster:
      category = kWheel;
      collide = kGround;
      break;
  }
  dGeomSetCategoryBits(geom, category);
  dGeomSetCollideBits(geom, collide);
}

}  // namespace ubersim::physics
