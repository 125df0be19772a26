// The jointed drive model (the paper's): chassis plus one body per wheel on a
// hinge joint, driven by an ODE velocity motor whose torque is capped at the
// motor's. Wheels collide with the floor only, as spheres (one contact point,
// exactly below the axle); the contact handler gives each wheel contact its
// rolling direction, with full friction along it and the roller friction
// across it.
//
// A robot told to stand (every set-point 0) grips the floor where it stopped:
// each wheel's floor contact takes the wheel back to where it stood
// (WheelGrip, contact_handler.cpp), as a tyre's static friction does. Without
// it the small tangential error QuickStep's few iterations leave every step
// adds up to a creep (about 0.6 mm/s and 0.2 deg/s for omni4_ssl standing
// alone). Pushed further than kGripGive, a wheel gives way and grips where it
// was pushed to.

#include <algorithm>
#include <cmath>

#include "ubersim/physics/drive.hpp"

namespace ubersim::physics {
namespace {

// m: the farthest a standing wheel is taken back to where it stopped.
constexpr double kGripGive = 0.003;

// Starts or keeps a standing wheel's grip; a wheel pushed further than
// kGripGive from its anchor takes the anchor along.
void grip_where_standing(dBodyID wheel, WheelGrip& grip) {
  const dReal* centre = dBodyGetPosition(wheel);
  if (!grip.active) {
    std::copy(centre, centre + 3, grip.anchor);
    grip.active = true;
    return;
  }
  double off[3];
  for (int k = 0; k < 3; ++k) off[k] = centre[k] - grip.anchor[k];
  const double distance = std::sqrt(off[0] * off[0] + off[1] * off[1] + off[2] * off[2]);
  if (distance <= kGripGive) return;
  for (int k = 0; k < 3; ++k) grip.anchor[k] = centre[k] - off[k] * kGripGive / distance;
}

class JointedDrive final : public Drive {
 public:
  explicit JointedDrive(const DriveContext& c) : type_(*c.type), kinematics_(*c.kinematics) {
    const RobotTypeConfig& t = type_;
    com_height_ = t.center_of_mass_height;
    chassis_.reset(dBodyCreate(c.world));
    const double n = static_cast<double>(t.wheels.size());
    const double chassis_mass = t.mass - n * t.wheel_mass;
    const double wheel_inertia = t.wheel_mass * t.wheel_radius * t.wheel_radius / 2;
    double wheels_yaw_inertia = 0;
    for (const auto& w : t.wheels) {
      wheels_yaw_inertia += t.wheel_mass * w.distance * w.distance + wheel_inertia;
    }
    const double tilt_inertia = chassis_mass * (3 * t.radius * t.radius + t.height * t.height) / 12;
    dMass m;
    dMassSetParameters(&m, chassis_mass, 0, 0, 0, tilt_inertia, tilt_inertia,
                       t.moment_of_inertia - wheels_yaw_inertia, 0, 0, 0);
    dBodySetMass(chassis_.get(), &m);
    geom_.reset(create_chassis_geom(c.space, c.outline));
    dGeomSetBody(geom_.get(), chassis_.get());
    tag_geom(geom_.get(), c.chassis_tag);

    for (const auto& config : t.wheels) {
      auto& w = wheels_.emplace_back();
      const WheelGeometry g = wheel_geometry(config);
      w.local[0] = g.x;
      w.local[1] = g.y;
      w.local[2] = t.wheel_radius - com_height_;
      // Axle along z x d: a positive hinge rate then drives the robot along d.
      w.axis[0] = -g.dy;
      w.axis[1] = g.dx;
      w.axis[2] = 0;
      w.body.reset(dBodyCreate(c.world));
      dMass wm;
      dMassSetParameters(&wm, t.wheel_mass, 0, 0, 0, wheel_inertia, wheel_inertia, wheel_inertia, 0,
                         0, 0);
      dBodySetMass(w.body.get(), &wm);
      w.geom.reset(dCreateSphere(c.space, t.wheel_radius));
      dGeomSetBody(w.geom.get(), w.body.get());
      w.hinge.reset(dJointCreateHinge(c.world, nullptr));
      w.tag.kind = GeomKind::Wheel;
      w.tag.robot = c.robot;
      w.tag.wheel_hinge = w.hinge.get();
      w.tag.grip = &w.grip;
      tag_geom(w.geom.get(), &w.tag);
    }
    for (std::size_t i = 0; i + 1 < t.caster_positions.size(); i += 2) {
      GeomHandle caster(dCreateSphere(c.space, t.caster_radius));
      dGeomSetBody(caster.get(), chassis_.get());
      dGeomSetOffsetPosition(caster.get(), t.caster_positions[i], t.caster_positions[i + 1],
                             t.caster_radius - com_height_);
      caster_tag_.kind = GeomKind::Caster;
      caster_tag_.robot = c.robot;
      tag_geom(caster.get(), &caster_tag_);
      casters_.push_back(std::move(caster));
    }
    place(PlanarState{});
    // Joints are attached once the bodies stand where they belong: ODE takes
    // the anchor and axis relative to the bodies' poses at this moment.
    for (auto& w : wheels_) {
      dJointAttach(w.hinge.get(), w.body.get(), chassis_.get());
      const dReal* p = dBodyGetPosition(w.body.get());
      dJointSetHingeAnchor(w.hinge.get(), p[0], p[1], p[2]);
      dJointSetHingeAxis(w.hinge.get(), w.axis[0], w.axis[1], w.axis[2]);
      dJointSetHingeParam(w.hinge.get(), dParamFMax, t.motor_max_torque);
      dJointSetHingeParam(w.hinge.get(), dParamVel, 0);
    }
  }

  dBodyID chassis() const override { return chassis_.get(); }
  dGeomID chassis_geom() const override { return geom_.get(); }

  void drive(const std::vector<double>& wheel_speeds, double /*dt*/) override {
    for (std::size_t i = 0; i < wheels_.size(); ++i) {
      dJointSetHingeParam(wheels_[i].hinge.get(), dParamVel, wheel_speeds[i]);
    }
    const bool standing =
        std::all_of(wheel_speeds.begin(), wheel_speeds.end(), [](double w) { return w == 0; });
    for (Wheel& w : wheels_) {
      if (standing) {
        grip_where_standing(w.body.get(), w.grip);
      } else {
        w.grip.active = false;
      }
    }
  }

  void measured_wheel_speeds(std::vector<double>& out) const override {
    out.resize(wheels_.size());
    for (std::size_t i = 0; i < wheels_.size(); ++i) {
      out[i] = dJointGetHingeAngleRate(wheels_[i].hinge.get());
    }
  }

  void place(const PlanarState& s) override {
    for (Wheel& w : wheels_) w.grip.active = false;  // a placed robot grips where it is placed
    place_chassis(chassis_.get(), s, com_height_);
    // Wheels upright with the chassis, rolling at the speed that matches the
    // placed velocity.
    dMatrix3 R;
    yaw_rotation(s.heading, R);
    const Eigen::VectorXd spin = rolling_wheel_speeds(kinematics_, s);
    for (std::size_t i = 0; i < wheels_.size(); ++i) {
      Wheel& w = wheels_[i];
      dVector3 p;
      dBodyGetRelPointPos(chassis_.get(), w.local[0], w.local[1], w.local[2], p);
      dBodySetPosition(w.body.get(), p[0], p[1], p[2]);
      dBodySetRotation(w.body.get(), R);
      dVector3 v;
      dBodyGetRelPointVel(chassis_.get(), w.local[0], w.local[1], w.local[2], v);
      dBodySetLinearVel(w.body.get(), v[0], v[1], v[2]);
      dVector3 axis;
      dBodyVectorToWorld(chassis_.get(), w.axis[0], w.axis[1], w.axis[2], axis);
      const double rate = spin(static_cast<Eigen::Index>(i));
      dBodySetAngularVel(w.body.get(), axis[0] * rate, axis[1] * rate, s.omega + axis[2] * rate);
      dBodySetForce(w.body.get(), 0, 0, 0);
      dBodySetTorque(w.body.get(), 0, 0, 0);
    }
  }

  void bodies(std::vector<dBodyID>& out) const override {
    out.push_back(chassis_.get());
    for (const auto& w : wheels_) out.push_back(w.body.get());
  }

 private:
  struct Wheel {
    BodyHandle body;
    GeomHandle geom;
    JointHandle hinge;
    GeomTag tag;
    double local[3] = {0, 0, 0};  // wheel centre relative to the chassis body (m)
    double axis[3] = {0, 0, 0};   // axle, chassis frame
    WheelGrip grip;               // its floor contact's static grip while standing
  };

  const RobotTypeConfig& type_;
  const WheelKinematics& kinematics_;
  double com_height_ = 0;
  // Joints before bodies in destruction order: declared after them.
  BodyHandle chassis_;
  GeomHandle geom_;
  std::deque<Wheel> wheels_;  // deque: tags must keep their addresses
  GeomTag caster_tag_;
  std::vector<GeomHandle> casters_;
};

}  // namespace

std::unique_ptr<Drive> make_jointed_drive(const DriveContext& context) {
  return std::make_unique<JointedDrive>(context);
}

}  // namespace ubersim::physics
