#include "ubersim/physics/contact_handler.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "ubersim/physics/robot.hpp"

namespace ubersim::physics {

ContactHandler::ContactHandler(const PhysicsConfig& physics, const FieldConfig& field,
                               const BallConfig& ball, const BallSurface& ball_surface)
    : physics_(physics),
      field_(field),
      ball_(ball),
      ball_surface_(ball_surface),
      buffer_(static_cast<std::size_t>(physics.max_contacts)) {}

void ContactHandler::collide(dSpaceID world_space, dWorldID world, dJointGroupID group) {
  world_ = world;
  group_ = group;
  contacts_ = 0;
  dSpaceCollide(world_space, this, &ContactHandler::near_callback);
}

void ContactHandler::near_callback(void* data, dGeomID a, dGeomID b) {
  auto* self = static_cast<ContactHandler*>(data);
  if (dGeomIsSpace(a) || dGeomIsSpace(b)) {
    // A robot's space (or the walls'): test its geoms, never against each other.
    dSpaceCollide2(a, b, data, &ContactHandler::near_callback);
    return;
  }
  self->touch(a, b);
}

void ContactHandler::touch(dGeomID a, dGeomID b) {
  const auto* ta = static_cast<const GeomTag*>(dGeomGetData(a));
  const auto* tb = static_cast<const GeomTag*>(dGeomGetData(b));
  if (ta == nullptr || tb == nullptr) return;
  if (ta->robot != nullptr && ta->robot == tb->robot) return;  // a robot's own parts
  // Wheels and ball casters are the robot's supports on the floor.
  auto is_support = [](GeomKind k) { return k == GeomKind::Wheel || k == GeomKind::Caster; };
  if (is_support(ta->kind) && tb->kind == GeomKind::Ground) {
    touch_support(a, b);
    return;
  }
  if (is_support(tb->kind) && ta->kind == GeomKind::Ground) {
    touch_support(b, a);
    return;
  }
  const int n = dCollide(a, b, physics_.max_contacts, buffer_.data(), sizeof(dContactGeom));
  if (n <= 0) return;
  const dBodyID body_a = dGeomGetBody(a);
  const dBodyID body_b = dGeomGetBody(b);
  for (int i = 0; i < n; ++i) {
    dContact contact{};
    contact.geom = buffer_[static_cast<std::size_t>(i)];
    surface_for(a, b, *ta, *tb, contact);
    const dJointID joint = dJointCreateContact(world_, group_, &contact);
    dJointAttach(joint, body_a, body_b);
    ++contacts_;
  }
}

namespace {

// Slower slip than this (m/s) counts as rolling.
constexpr double kSlipThreshold = 1e-3;

// The part of v across `normal`, as a unit vector, if longer than `minimum`.
bool tangent_direction(const double* v, const double* normal, double minimum, double* out) {
  const double along = v[0] * normal[0] + v[1] * normal[1] + v[2] * normal[2];
  const double t[3] = {v[0] - along * normal[0], v[1] - along * normal[1],
                       v[2] - along * normal[2]};
  const double length = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
  if (length <= minimum || length < 1e-12) return false;
  for (int k = 0; k < 3; ++k) out[k] = t[k] / length;
  return true;
}

// 1/s: a standing wheel's contact moves back towards its anchor at this rate
// times its distance from it (a 50 ms time constant).
constexpr double kGripGain = 20.0;

// A standing wheel's static grip: the contact's two friction rows ask for the
// velocity that takes the wheel centre back to its anchor, as a tyre's
// deflection under static friction does, instead of for none. Without it
// the tangential error QuickStep's few iterations leave every step is never
// taken back, and a robot told to stand creeps (0.6 mm/s and 0.2 deg/s for
// omni4_ssl). The rows keep their force bounds (the wheel's friction), so a
// robot pushed harder still slides. The contact's body 1 is the wheel.
void hold_grip(const WheelGrip& grip, const dReal* centre, dContact& c) {
  const double* n = c.geom.normal;
  const double* t1 = c.fdir1;
  const double t2[3] = {n[1] * t1[2] - n[2] * t1[1], n[2] * t1[0] - n[0] * t1[2],
                        n[0] * t1[1] - n[1] * t1[0]};  // ODE's second direction: n x t1
  const double off[3] = {centre[0] - grip.anchor[0], centre[1] - grip.anchor[1],
                         centre[2] - grip.anchor[2]};
  c.surface.mode |= dContactMotion1 | dContactMotion2;
  c.surface.motion1 = -kGripGain * (off[0] * t1[0] + off[1] * t1[1] + off[2] * t1[2]);
  c.surface.motion2 = -kGripGain * (off[0] * t2[0] + off[1] * t2[1] + off[2] * t2[2]);
}

}  // namespace

void ContactHandler::touch_support(dGeomID support, dGeomID ground) {
  // A wheel or caster touches the floor within a small margin, not only when
  // it sinks in: four wheels (or wheels and casters) on one rigid chassis are
  // statically indeterminate, and a support hovering a rounding error above
  // the floor would otherwise lose its grip, or (a caster) come and go from
  // one step to the next and knock the chassis each time it comes back.
  dVector4 plane;
  dGeomPlaneGetParams(ground, plane);
  const dReal* centre = dGeomGetPosition(support);
  const double radius = dGeomSphereGetRadius(support);
  const double gap =
      plane[0] * centre[0] + plane[1] * centre[1] + plane[2] * centre[2] - plane[3] - radius;
  if (gap > physics_.wheel_contact_margin) return;
  dContact contact{};
  // The contact point is on the unloaded rim (one radius below the centre),
  // not on the floor: a compliant tyre sinks a little (WHEEL_CONTACT_STIFFNESS),
  // and a contact at the floor would make the wheel roll on a smaller radius,
  // i.e. drive a few per cent slower than its encoders say.
  for (int k = 0; k < 3; ++k) {
    contact.geom.pos[k] = centre[k] - plane[k] * radius;
    contact.geom.normal[k] = plane[k];
  }
  contact.geom.depth = std::max(0.0, -gap);
  contact.geom.g1 = support;
  contact.geom.g2 = ground;
  contact.geom.side1 = contact.geom.side2 = -1;
  const auto* support_tag = static_cast<const GeomTag*>(dGeomGetData(support));
  surface_for(support, ground, *support_tag, *static_cast<const GeomTag*>(dGeomGetData(ground)),
              contact);
  const dJointID joint = dJointCreateContact(world_, group_, &contact);
  dJointAttach(joint, dGeomGetBody(support), nullptr);
  ++contacts_;
}

void ContactHandler::surface_for(dGeomID a, dGeomID b, const GeomTag& ta, const GeomTag& tb,
                                 dContact& c) const {
  dSurfaceParameters& s = c.surface;
  s.bounce_vel = physics_.bounce_min_velocity;
  // Order the pair so that each case below is written once.
  GeomKind ka = ta.kind;
  GeomKind kb = tb.kind;
  if (static_cast<int>(ka) > static_cast<int>(kb)) std::swap(ka, kb);
  auto is = [&](GeomKind x, GeomKind y) { return ka == x && kb == y; };

  if (is(GeomKind::Ground, GeomKind::Ball)) {
    // Carpet: Coulomb friction (proportional to the load), rolling resistance,
    // bounce. Friction acts along the sliding direction, so a ball sliding
    // diagonally decelerates exactly like one sliding along an axis.
    s.mode = dContactApprox1 | dContactRolling | dContactBounce;
    s.mu = ball_surface_.ground_friction;
    s.rho = ball_surface_.rolling_friction;
    s.bounce = ball_.bounce_restitution;
    // Both friction and rolling resistance act in the box of ODE's two
    // tangent axes; aligning the first with the motion makes them act along
    // it exactly, so a ball moving diagonally behaves like one along an axis.
    // While sliding that is the slip of the contact point, once rolling the
    // ball's own direction.
    const dGeomID ball = ta.kind == GeomKind::Ball ? a : b;
    const dBodyID body = dGeomGetBody(ball);
    dVector3 slip;
    dBodyGetPointVel(body, c.geom.pos[0], c.geom.pos[1], c.geom.pos[2], slip);
    const double* v = dBodyGetLinearVel(body);
    if (!tangent_direction(slip, c.geom.normal, kSlipThreshold, c.fdir1) &&
        !tangent_direction(v, c.geom.normal, 0.0, c.fdir1)) {
      return;
    }
    s.mode |= dContactFDir1;
  } else if (is(GeomKind::Ground, GeomKind::Wheel)) {
    // Omni wheel or tyre: grip along the rolling direction (axle x normal),
    // roller friction across it. The friction bounds use each wheel's static
    // share of the robot's weight rather than the solver's normal force: with
    // casters and wheels on one rigid chassis the load split is statically
    // indeterminate, and an iterative solver's split (and hence the grip)
    // would be arbitrary. The planar model uses the same loads.
    s.mode = dContactMu2 | dContactFDir1;
    const GeomTag& w = ta.kind == GeomKind::Wheel ? ta : tb;
    dVector3 axle;
    dJointGetHingeAxis(w.wheel_hinge, axle);
    const double* n = c.geom.normal;
    double d[3] = {axle[1] * n[2] - axle[2] * n[1], axle[2] * n[0] - axle[0] * n[2],
                   axle[0] * n[1] - axle[1] * n[0]};
    const double len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (len > 1e-9) {
      for (int k = 0; k < 3; ++k) c.fdir1[k] = d[k] / len;
    } else {
      s.mode &= ~dContactFDir1;
    }
    const RobotTypeConfig& type = w.robot->type();
    const auto supports = static_cast<double>(type.wheel_count() + type.caster_count());
    const double load = type.mass * physics_.gravity / supports;
    s.mu = type.wheel_friction * load;
    s.mu2 = type.wheel_lateral_friction * load;
    // The tyre is a stiff spring and damper, not a rigid support: ODE's
    // ERP/CFM for a spring k and damper c over one step h. Besides being
    // what a tyre is, this makes the support (wheels plus casters on a rigid
    // chassis) determinate for the solver: with rigid contacts QuickStep's
    // few iterations leave the two wheels of a differential drive with
    // unbalanced forces that yaw it (docs/physics.md, "Tyre compliance").
    const double spring_per_step = type.wheel_contact_stiffness * physics_.dt();
    const double denominator = spring_per_step + type.wheel_contact_damping;
    s.mode |= dContactSoftERP | dContactSoftCFM;
    s.soft_erp = spring_per_step / denominator;
    s.soft_cfm = 1.0 / denominator;
    if (w.grip != nullptr && w.grip->active) {
      hold_grip(*w.grip, dGeomGetPosition(ta.kind == GeomKind::Wheel ? a : b), c);
    }
  } else if (is(GeomKind::Ground, GeomKind::Chassis)) {
    s.mode = dContactApprox1;
    s.mu = physics_.chassis_ground_friction;
  } else if (is(GeomKind::Wall, GeomKind::Ball) || is(GeomKind::Wall, GeomKind::Chassis)) {
    s.mode = dContactApprox1 | dContactBounce;
    s.mu = field_.wall_friction;
    s.bounce = field_.wall_restitution;
  } else if (is(GeomKind::Ball, GeomKind::Chassis)) {
    s.mode = dContactApprox1 | dContactBounce;
    s.mu = physics_.ball_robot_friction;
    s.bounce = ball_.robot_restitution;
  } else if (is(GeomKind::Chassis, GeomKind::Chassis)) {
    s.mode = dContactApprox1 | dContactBounce;
    s.mu = physics_.robot_robot_friction;
    s.bounce = physics_.robot_robot_restitution;
  } else {
    // Ground and Caster: ball casters roll freely every way (and nothing else
    // reaches here: the collide bits filter every other pair).
    s.mode = 0;
    s.mu = 0;
  }
}

}  // namespace ubersim::physics
