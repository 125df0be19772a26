#include "bare_ode_scene.hpp"

#include <algorithm>
#include <cmath>

namespace ubersim::physics::bench {
namespace {

constexpr int kMaxContacts = 4;

void add_box(dSpaceID space, double x, double y, double lx, double ly, double h) {
  dGeomID g = dCreateBox(space, lx, ly, h);
  dGeomSetPosition(g, x, y, h / 2);
}

}  // namespace

BareOdeScene::BareOdeScene(const WorldSetup& setup, DriveModel model)
    : model_(model), dt_(setup.physics.dt()) {
  ensure_ode_initialised();
  const PhysicsConfig& p = setup.physics;
  world_ = dWorldCreate();
  dWorldSetGravity(world_, 0, 0, -p.gravity);
  dWorldSetERP(world_, p.erp);
  dWorldSetCFM(world_, p.cfm);
  dWorldSetQuickStepNumIterations(world_, p.solver_iterations);
  dWorldSetQuickStepW(world_, p.solver_sor);
  dWorldSetContactMaxCorrectingVel(world_, p.contact_max_correcting_velocity);
  dWorldSetContactSurfaceLayer(world_, p.contact_surface_layer);
  space_ = dSimpleSpaceCreate(nullptr);
  static_space_ = dSimpleSpaceCreate(space_);
  contacts_ = dJointGroupCreate(0);
  dCreatePlane(space_, 0, 0, 1, 0);
  const FieldConfig& f = setup.field;
  const double hx = f.half_length_to_wall(), hy = f.half_width_to_wall(), t = f.wall_thickness;
  add_box(static_space_, 0, hy + t / 2, 2 * (hx + t), t, f.wall_height);
  add_box(static_space_, 0, -hy - t / 2, 2 * (hx + t), t, f.wall_height);
  add_box(static_space_, hx + t / 2, 0, t, 2 * hy, f.wall_height);
  add_box(static_space_, -hx - t / 2, 0, t, 2 * hy, f.wall_height);
  for (double s : {-1.0, 1.0}) {
    const double gx = f.field_length / 2, gd = f.goal_depth, gt = f.goal_wall_thickness;
    add_box(static_space_, s * (gx + gd + gt / 2), 0, gt, f.goal_width + 2 * gt, f.goal_height);
    add_box(static_space_, s * (gx + gd / 2), f.goal_width / 2 + gt / 2, gd, gt, f.goal_height);
    add_box(static_space_, s * (gx + gd / 2), -f.goal_width / 2 - gt / 2, gd, gt, f.goal_height);
  }

  ball_ = dBodyCreate(world_);
  dMass bm;
  dMassSetSphereTotal(&bm, setup.ball.mass, setup.ball.radius);
  dBodySetMass(ball_, &bm);
  dGeomID ball_geom = dCreateSphere(space_, setup.ball.radius);
  dGeomSetBody(ball_geom, ball_);
  dBodySetPosition(ball_, setup.ball_x, setup.ball_y, setup.ball.radius);

  for (const RobotSpawn& spawn : setup.robots) {
    const auto type_ptr = setup.robot_types(spawn.type);
    const RobotTypeConfig& type = *type_ptr;
    Robot r;
    r.space = dSimpleSpaceCreate(space_);
    r.chassis = dBodyCreate(world_);
    r.wheel_radius = type.wheel_radius;
    r.mass = type.mass;
    r.inertia = type.moment_of_inertia;
    r.max_force = type.wheel_friction * type.mass * p.gravity;
    r.max_acceleration = type.max_acceleration;
    r.max_angular_acceleration = type.max_angular_acceleration;
    dMatrix3 R;
    dRFromAxisAndAngle(R, 0, 0, 1, spawn.state.heading);
    dMass m;
    const bool jointed = model == DriveModel::Jointed;
    const double chassis_mass =
        jointed ? type.mass - type.wheel_mass * static_cast<double>(type.wheels.size()) : type.mass;
    dMassSetCylinderTotal(&m, chassis_mass, 3, type.radius, type.height);
    dBodySetMass(r.chassis, &m);
    const double z = jointed ? type.center_of_mass_height : 0.0;
    dBodySetPosition(r.chassis, spawn.state.x, spawn.state.y, z);
    dBodySetRotation(r.chassis, R);
    // The nearest native ODE shape to the SSL chassis.
    dGeomID chassis = dCreateCylinder(r.space, type.radius, type.height - type.ground_clearance);
    dGeomSetBody(chassis, r.chassis);
    dGeomSetOffsetPosition(chassis, 0, 0,
                           (type.height + type.ground_clearance) / 2 - (jointed ? z : 0.0));
    if (jointed) {
      for (const auto& wc : type.wheels) {
        Wheel w;
        w.x = wc.distance * std::cos(wc.angle);
        w.y = wc.distance * std::sin(wc.angle);
        w.dx = wc.drive_x;
        w.dy = wc.drive_y;
        w.body = dBodyCreate(world_);
        dMass wm;
        dMassSetSphereTotal(&wm, type.wheel_mass, type.wheel_radius);
        dBodySetMass(w.body, &wm);
        dVector3 pos;
        dBodyGetRelPointPos(r.chassis, w.x, w.y, type.wheel_radius - z, pos);
        dBodySetPosition(w.body, pos[0], pos[1], pos[2]);
        dBodySetRotation(w.body, R);
        dGeomID wg = dCreateSphere(r.space, type.wheel_radius);
        dGeomSetBody(wg, w.body);
        w.hinge = dJointCreateHinge(world_, nullptr);
        dJointAttach(w.hinge, w.body, r.chassis);
        dJointSetHingeAnchor(w.hinge, pos[0], pos[1], pos[2]);
        dVector3 axis;
        dBodyVectorToWorld(r.chassis, -w.dy, w.dx, 0, axis);
        dJointSetHingeAxis(w.hinge, axis[0], axis[1], axis[2]);
        dJointSetHingeParam(w.hinge, dParamFMax, type.motor_max_torque);
        r.wheels.push_back(w);
      }
    } else {
      dBodySetGravityMode(r.chassis, 0);
      dJointID plane = dJointCreatePlane2D(world_, nullptr);
      dJointAttach(plane, r.chassis, nullptr);
    }
    robots_.push_back(r);
  }
}

BareOdeScene::~BareOdeScene() {
  dJointGroupDestroy(contacts_);
  dSpaceDestroy(space_);  // and, by ODE's default cleanup, every geom and sub-space
  dWorldDestroy(world_);
}

void BareOdeScene::command(std::size_t index, double vx, double vy, double omega) {
  Robot& r = robots_[index];
  r.target[0] = vx;
  r.target[1] = vy;
  r.target[2] = omega;
}

void BareOdeScene::near_callback(void* data, dGeomID a, dGeomID b) {
  auto* self = static_cast<BareOdeScene*>(data);
  if (dGeomIsSpace(a) || dGeomIsSpace(b)) {
    if (a == reinterpret_cast<dGeomID>(self->static_space_) ||
        b == reinterpret_cast<dGeomID>(self->static_space_)) {
      if (dGeomGetClass(a) == dPlaneClass || dGeomGetClass(b) == dPlaneClass) return;
    }
    dSpaceCollide2(a, b, data, &near_callback);
    return;
  }
  const dBodyID ba = dGeomGetBody(a), bb = dGeomGetBody(b);
  if (ba == nullptr && bb == nullptr) return;
  dContactGeom geoms[kMaxContacts];
  const int n = dCollide(a, b, kMaxContacts, geoms, sizeof(dContactGeom));
  for (int i = 0; i < n; ++i) {
    dContact c{};
    c.geom = geoms[i];
    c.surface.mode = dContactApprox1 | dContactBounce;
    c.surface.mu = 0.5;
    c.surface.bounce = 0.5;
    c.surface.bounce_vel = 0.1;
    dJointID j = dJointCreateContact(self->world_, self->contacts_, &c);
    dJointAttach(j, ba, bb);
  }
}

void BareOdeScene::step() {
  for (Robot& r : robots_) {
    // The same on-board acceleration limit as ubersim's robots, so both
    // scenes move alike.
    const dReal* R = dBodyGetRotation(r.chassis);
    const double c = R[0], s = R[4];
    const double want[3] = {c * r.target[0] - s * r.target[1], s * r.target[0] + c * r.target[1],
                            r.target[2]};
    const double dv = r.max_acceleration * dt_, dw = r.max_angular_acceleration * dt_;
    for (int k = 0; k < 3; ++k) {
      const double limit = k < 2 ? dv : dw;
      r.setpoint[k] += std::clamp(want[k] - r.setpoint[k], -limit, limit);
    }
    if (model_ == DriveModel::Jointed) {
      const double local[2] = {c * r.setpoint[0] + s * r.setpoint[1],
                               -s * r.setpoint[0] + c * r.setpoint[1]};
      for (Wheel& w : r.wheels) {
        const double speed =
            (w.dx * local[0] + w.dy * local[1] + r.setpoint[2] * (w.x * w.dy - w.y * w.dx)) /
            r.wheel_radius;
        dJointSetHingeParam(w.hinge, dParamVel, speed);
      }
    } else {
      const dReal* v = dBodyGetLinearVel(r.chassis);
      const dReal* w = dBodyGetAngularVel(r.chassis);
      const double fx =
          std::clamp(r.mass * (r.setpoint[0] - v[0]) / dt_, -r.max_force, r.max_force);
      const double fy =
          std::clamp(r.mass * (r.setpoint[1] - v[1]) / dt_, -r.max_force, r.max_force);
      dBodyAddForce(r.chassis, fx, fy, 0);
      dBodyAddTorque(r.chassis, 0, 0, r.inertia * (r.setpoint[2] - w[2]) / dt_);
    }
  }
  dSpaceCollide(space_, this, &near_callback);
  dWorldQuickStep(world_, dt_);
  dJointGroupEmpty(contacts_);
}

}  // namespace ubersim::physics::bench
