#include "ubersim/physics/field_builder.hpp"

namespace ubersim::physics {
namespace {

void add_box(StaticField& f, double cx, double cy, double lx, double ly, double height) {
  GeomHandle box(dCreateBox(f.space.get(), lx, ly, height));
  dGeomSetPosition(box.get(), cx, cy, height / 2);
  tag_geom(box.get(), &f.wall_tag);
  f.walls.push_back(std::move(box));
}

}  // namespace

std::unique_ptr<StaticField> build_field(const FieldConfig& field, dSpaceID world_space) {
  auto f = std::make_unique<StaticField>();
  f->space = make_simple_space(world_space);
  f->ground.reset(dCreatePlane(world_space, 0, 0, 1, 0));
  tag_geom(f->ground.get(), &f->ground_tag);
  // The walls' space is a geom of the world space too: give it the walls' bits
  // so that the floor and it never test against each other.
  dGeomSetCategoryBits(reinterpret_cast<dGeomID>(f->space.get()), collide_bits::kWall);
  dGeomSetCollideBits(reinterpret_cast<dGeomID>(f->space.get()),
                      collide_bits::kBall | collide_bits::kChassis);

  // Boundary walls: inner faces at the wall lines, the long ones covering the corners.
  const double hx = field.half_length_to_wall();
  const double hy = field.half_width_to_wall();
  const double t = field.wall_thickness;
  const double h = field.wall_height;
  add_box(*f, 0, hy + t / 2, 2 * (hx + t), t, h);
  add_box(*f, 0, -(hy + t / 2), 2 * (hx + t), t, h);
  add_box(*f, hx + t / 2, 0, t, 2 * hy, h);
  add_box(*f, -(hx + t / 2), 0, t, 2 * hy, h);

  // Goals: open towards the field, inner mouth on the goal line.
  const double gx = field.field_length / 2;
  const double gw = field.goal_width;
  const double gd = field.goal_depth;
  const double gt = field.goal_wall_thickness;
  const double gh = field.goal_height;
  for (double side : {-1.0, 1.0}) {
    add_box(*f, side * (gx + gd + gt / 2), 0, gt, gw + 2 * gt, gh);
    add_box(*f, side * (gx + gd / 2), gw / 2 + gt / 2, gd, gt, gh);
    add_box(*f, side * (gx + gd / 2), -(gw / 2 + gt / 2), gd, gt, gh);
  }
  return f;
}

}  // namespace ubersim::physics
