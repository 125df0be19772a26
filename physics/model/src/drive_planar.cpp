// The planar drive model: one body per robot, held to the floor plane by a
// plane-2D joint, with no wheel bodies. Each step solves, per robot, for the
// wheel forces that would make every wheel roll at its set-point and not slide
// across its axle, each force bounded: along the wheel by the smaller of the
// motor's torque / wheel radius and Coulomb friction, across it by the roller
// (or tyre) friction. It is a small projected Gauss-Seidel over 2 rows per
// wheel and 3 degrees of freedom; the forces go to ODE as forces at the wheels'
// contact points, so everything else (collisions, kicks) stays ODE physics.
//
// Most steps need no iteration: when the set-points describe one rigid motion
// of the chassis (they do whenever they come from the inverse kinematics) and
// no wheel needs more than its bound to reach it, the solve's answer is that
// motion, reached this step. That case is checked and solved directly (a few
// fixed-size products, no dependency chain); the iteration handles the rest
// (saturated wheels, wheel-speed commands that fight each other).
#include <algorithm>
#include <array>
#include <cmath>

#include "ubersim/physics/drive.hpp"
#include "ubersim/physics/heading.hpp"

namespace ubersim::physics {
namespace {

// An impulse change below this (N s) changes no velocity that matters: under
// a micrometre per second on a robot.
constexpr double kConverged = 1e-6;
// Out-of-plane tilt (unitless), height (m) and speeds (m/s, rad/s) summed:
// below this a planar robot is left alone.
constexpr double kPlanarDrift = 1e-9;
// Wheel surface speeds (m/s) that miss a rigid motion of the chassis by less
// than this describe one: a micrometre per second.
constexpr double kRigidMotion = 1e-6;

class PlanarDrive final : public Drive {
 public:
  explicit PlanarDrive(const DriveContext& c)
      : type_(*c.type),
        kinematics_(*c.kinematics),
        iterations_(c.physics->planar_solver_iterations) {
    const RobotTypeConfig& t = type_;
    chassis_.reset(dBodyCreate(c.world));
    const double tilt_inertia = t.mass * (3 * t.radius * t.radius + t.height * t.height) / 12;
    dMass m;
    dMassSetParameters(&m, t.mass, 0, 0, 0, tilt_inertia, tilt_inertia, t.moment_of_inertia, 0, 0,
                       0);
    dBodySetMass(chassis_.get(), &m);
    // The plane-2D joint carries the weight; gravity would only load it.
    dBodySetGravityMode(chassis_.get(), 0);
    geom_.reset(create_chassis_geom(c.space, c.outline));
    dGeomSetBody(geom_.get(), chassis_.get());
    tag_geom(geom_.get(), c.chassis_tag);
    plane_.reset(dJointCreatePlane2D(c.world, nullptr));
    dJointAttach(plane_.get(), chassis_.get(), nullptr);

    // Static load share: the robot's weight spread over wheels and casters.
    const auto supports = static_cast<double>(t.wheel_count() + t.caster_count());
    const double load = t.mass * c.physics->gravity / supports;
    traction_limit_ = std::min(t.motor_max_torque / t.wheel_radius, t.wheel_friction * load);
    torque_limited_ = t.motor_max_torque / t.wheel_radius <= t.wheel_friction * load;
    lateral_limit_ = t.wheel_lateral_friction * load;
    for (const auto& w : t.wheels) wheels_.push_back(wheel_geometry(w));
    inverse_mass_ = 1 / t.mass;
    inverse_inertia_ = 1 / t.moment_of_inertia;
    measured_.assign(wheels_.size(), 0);
    rows_.resize(2 * wheels_.size());
    for (std::size_t i = 0; i < wheels_.size(); ++i) {
      const WheelGeometry& g = wheels_[i];
      const Vec2 d{g.dx, g.dy};
      set_row(rows_[2 * i], {g.x, g.y}, d);
      set_row(rows_[2 * i + 1], {g.x, g.y}, perp(d));
    }
    prepare_direct_solve();
    place(PlanarState{});
  }

  dBodyID chassis() const override { return chassis_.get(); }
  dGeomID chassis_geom() const override { return geom_.get(); }

  void drive(const std::vector<double>& wheel_speeds, double dt) override {
    // Solved in the robot's frame, where every row's Jacobian and effective
    // mass are constants (computed once, in the constructor).
    const dReal* lv = dBodyGetLinearVel(chassis_.get());
    const dReal* av = dBodyGetAngularVel(chassis_.get());
    const dReal* R = dBodyGetRotation(chassis_.get());
    const Vec2 heading = heading_direction(R);
    const double c = heading.x;
    const double s = heading.y;
    double v[3] = {c * lv[0] + s * lv[1], -s * lv[0] + c * lv[1], av[2]};
    for (std::size_t i = 0; i < wheels_.size(); ++i) {
      rows_[2 * i].target = wheel_speeds[i] * type_.wheel_radius;
      rows_[2 * i].bound = traction_limit_ * dt;
      rows_[2 * i + 1].target = 0;
      rows_[2 * i + 1].bound = lateral_limit_ * dt;
    }
    if (!solve_directly(v)) solve_iteratively(v, dt);
    double force[3] = {0, 0, 0};  // robot frame: x, y, yaw torque
    for (Row& row : rows_) {
      row.warm = row.impulse / dt;
      for (int k = 0; k < 3; ++k) force[k] += row.j[k] * row.warm;
    }
    dBodyAddForce(chassis_.get(), c * force[0] - s * force[1], s * force[0] + c * force[1], 0);
    dBodyAddTorque(chassis_.get(), 0, 0, force[2]);

    // Encoders: a wheel turns at its set-point unless its motor is out of
    // torque, in which case it rolls with the floor.
    for (std::size_t i = 0; i < wheels_.size(); ++i) {
      const Row& row = rows_[2 * i];
      const bool saturated = std::abs(row.impulse) >= row.bound * (1 - 1e-9);
      if (saturated && torque_limited_) {
        measured_[i] = row.along(v) / type_.wheel_radius;
      } else {
        measured_[i] = wheel_speeds[i];
      }
    }
  }

  // The projected Gauss-Seidel: updates the rows' impulses and v (robot
  // frame velocity after them).
  void solve_iteratively(double v[3], double dt) {
    // Warm start: last step's forces are nearly this step's, so a few
    // iterations from there converge where many from zero would be needed.
    for (Row& row : rows_) {
      row.impulse = std::clamp(row.warm * dt, -row.bound, row.bound);
      v[0] += row.j[0] * row.impulse * inverse_mass_;
      v[1] += row.j[1] * row.impulse * inverse_mass_;
      v[2] += row.j[2] * row.impulse * inverse_inertia_;
    }
    for (int it = 0; it < iterations_; ++it) {
      double largest_change = 0;
      for (Row& row : rows_) {
        const double jv = row.along(v);
        const double wanted = row.impulse + (row.target - jv) * row.mass;
        const double clamped = std::clamp(wanted, -row.bound, row.bound);
        const double delta = clamped - row.impulse;
        row.impulse = clamped;
        v[0] += row.j[0] * delta * inverse_mass_;
        v[1] += row.j[1] * delta * inverse_mass_;
        v[2] += row.j[2] * delta * inverse_inertia_;
        largest_change = std::max(largest_change, std::abs(delta));
      }
      // Converged (a robot at rest or cruising, thanks to the warm start).
      if (largest_change < kConverged) break;
    }
  }

  // The rigid motion the set-points ask for, if they ask for one, reached in
  // one step when no driving row needs more than its bound. Rows outside the
  // fit (an omni wheel's rollers) slide at that motion, so they push at their
  // bound against the slide, as the iteration would converge to. Returns
  // false (and changes nothing) otherwise.
  bool solve_directly(double v[3]) {
    if (!direct_solve_possible_) return false;
    double wanted[3] = {0, 0, 0};  // least-squares chassis velocity for the targets
    for (std::size_t r : fit_rows_) {
      for (int k = 0; k < 3; ++k) wanted[k] += fit_[r][k] * rows_[r].target;
    }
    for (std::size_t r : fit_rows_) {
      const Row& row = rows_[r];
      if (std::abs(row.along(wanted) - row.target) > kRigidMotion) return false;  // wheels fight
    }
    double impulse[3] = {(wanted[0] - v[0]) / inverse_mass_, (wanted[1] - v[1]) / inverse_mass_,
                         (wanted[2] - v[2]) / inverse_inertia_};
    for (std::size_t r : sliding_rows_) {
      const Row& row = rows_[r];
      const double slide = row.along(wanted) - row.target;
      shares_[r] = std::abs(slide) > kRigidMotion ? (slide > 0 ? -row.bound : row.bound) : 0.0;
      for (int k = 0; k < 3; ++k) impulse[k] -= row.j[k] * shares_[r];
    }
    for (std::size_t r : fit_rows_) {
      const auto& share = share_[r];
      shares_[r] = share[0] * impulse[0] + share[1] * impulse[1] + share[2] * impulse[2];
      if (std::abs(shares_[r]) > rows_[r].bound) return false;  // a wheel saturates: iterate
    }
    for (std::size_t r = 0; r < rows_.size(); ++r) rows_[r].impulse = shares_[r];
    for (int k = 0; k < 3; ++k) v[k] = wanted[k];
    return true;
  }

  // The fit uses the rolling rows when they alone fix the chassis' motion
  // (three or more omni wheels), else every row (a differential drive's
  // tyres fix the sideways motion). With J the fit rows' Jacobian (n x 3):
  // targets t describe a rigid motion when J w = t for w = (J^T J)^-1 J^T t.
  // A chassis impulse P is shared out as lambda = B J (J^T B J)^-1 P,
  // B = diag(bound^2): the shares that add up to P with the smallest sum of
  // (lambda / bound)^2, i.e. the furthest from saturating any row.
  void prepare_direct_solve() {
    fit_rows_.clear();
    sliding_rows_.clear();
    for (std::size_t r = 0; r < rows_.size(); r += 2) fit_rows_.push_back(r);
    if (rank_of(fit_rows_, false) < 3) {
      for (std::size_t r = 1; r < rows_.size(); r += 2) fit_rows_.push_back(r);
    } else {
      for (std::size_t r = 1; r < rows_.size(); r += 2) sliding_rows_.push_back(r);
    }
    // Rank below 3: no single motion fits, or no way to push it; iterate.
    direct_solve_possible_ = rank_of(fit_rows_, false) == 3 && rank_of(fit_rows_, true) == 3;
    fit_.assign(rows_.size(), {0, 0, 0});
    share_.assign(rows_.size(), {0, 0, 0});
    shares_.assign(rows_.size(), 0);
    if (!direct_solve_possible_) return;
    const Eigen::MatrixXd J = jacobian(fit_rows_, false);
    const Eigen::MatrixXd BJ = jacobian(fit_rows_, true);
    const Eigen::MatrixXd fit = (J.transpose() * J).inverse() * J.transpose();  // 3 x n
    const Eigen::MatrixXd share = BJ * (J.transpose() * BJ).inverse();          // n x 3
    for (std::size_t i = 0; i < fit_rows_.size(); ++i) {
      const auto row = static_cast<Eigen::Index>(i);
      for (int k = 0; k < 3; ++k) {
        fit_[fit_rows_[i]][static_cast<std::size_t>(k)] = fit(k, row);
        share_[fit_rows_[i]][static_cast<std::size_t>(k)] = share(row, k);
      }
    }
  }

  // The given rows' Jacobian, each row weighted by its bound squared if asked.
  Eigen::MatrixXd jacobian(const std::vector<std::size_t>& rows, bool weighted) const {
    Eigen::MatrixXd J(static_cast<Eigen::Index>(rows.size()), 3);
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const std::size_t r = rows[i];
      const double bound = r % 2 == 0 ? traction_limit_ : lateral_limit_;  // per unit time
      const double w = weighted ? bound * bound : 1.0;
      J.row(static_cast<Eigen::Index>(i)) << w * rows_[r].j[0], w * rows_[r].j[1],
          w * rows_[r].j[2];
    }
    return J;
  }

  Eigen::Index rank_of(const std::vector<std::size_t>& rows, bool weighted) const {
    const Eigen::MatrixXd J = jacobian(rows, false);
    return (J.transpose() * jacobian(rows, weighted)).fullPivLu().rank();
  }

  void after_step() override {
    // The plane-2D joint keeps velocities planar, but rounding still tilts and
    // lifts the body a little; project it back onto the plane (as ODE
    // advises) once that is measurable, not every step.
    const dReal* R = dBodyGetRotation(chassis_.get());
    const dReal* p = dBodyGetPosition(chassis_.get());
    const dReal* lv = dBodyGetLinearVel(chassis_.get());
    const dReal* av = dBodyGetAngularVel(chassis_.get());
    if (std::abs(R[8]) + std::abs(R[9]) + std::abs(p[2]) + std::abs(lv[2]) + std::abs(av[0]) +
            std::abs(av[1]) <
        kPlanarDrift) {
      return;
    }
    const Vec2 heading = heading_direction(R);
    dMatrix3 upright;
    yaw_rotation(heading.x, heading.y, upright);
    dBodySetRotation(chassis_.get(), upright);
    dBodySetPosition(chassis_.get(), p[0], p[1], 0);
    dBodySetLinearVel(chassis_.get(), lv[0], lv[1], 0);
    dBodySetAngularVel(chassis_.get(), 0, 0, av[2]);
  }

  void measured_wheel_speeds(std::vector<double>& out) const override { out = measured_; }

  void place(const PlanarState& s) override {
    place_chassis(chassis_.get(), s, 0);
    const Eigen::VectorXd spin = rolling_wheel_speeds(kinematics_, s);
    for (std::size_t i = 0; i < measured_.size(); ++i) {
      measured_[i] = spin(static_cast<Eigen::Index>(i));
    }
    for (Row& row : rows_) row.warm = 0;
  }

  void bodies(std::vector<dBodyID>& out) const override { out.push_back(chassis_.get()); }

 private:
  struct Row {
    // Contact velocity along the row (m/s) for a robot-frame velocity v.
    double along(const double v[3]) const { return j[0] * v[0] + j[1] * v[1] + j[2] * v[2]; }

    double j[3] = {0, 0,
                   0};   // Jacobian, robot frame: (x, y, yaw) -> contact velocity along the row
    double target = 0;   // m/s
    double bound = 0;    // N s, largest impulse this step
    double mass = 0;     // effective mass along the row (kg)
    double impulse = 0;  // N s, accumulated this step
    double warm = 0;     // N, last step's force: where the next solve starts
  };

  // A row along `direction` at contact point r (robot frame).
  void set_row(Row& row, Vec2 r, Vec2 direction) const {
    row.j[0] = direction.x;
    row.j[1] = direction.y;
    row.j[2] = cross(r, direction);
    row.mass = 1 / (inverse_mass_ * (direction.x * direction.x + direction.y * direction.y) +
                    inverse_inertia_ * row.j[2] * row.j[2]);
  }

  const RobotTypeConfig& type_;
  const WheelKinematics& kinematics_;
  int iterations_;
  BodyHandle chassis_;
  GeomHandle geom_;
  JointHandle plane_;
  std::vector<WheelGeometry> wheels_;
  std::vector<Row> rows_;
  // Direct solve (prepare_direct_solve): per row, its column of the fit and
  // its share of a chassis impulse; shares_ is scratch for one step.
  bool direct_solve_possible_ = false;
  std::vector<std::size_t> fit_rows_;      // rows whose targets fix the motion
  std::vector<std::size_t> sliding_rows_;  // the others: omni rollers
  std::vector<std::array<double, 3>> fit_;
  std::vector<std::array<double, 3>> share_;
  std::vector<double> shares_;
  std::vector<double> measured_;
  double traction_limit_ = 0;  // N
  bool torque_limited_ = false;
  double lateral_limit_ = 0;  // N
  double inverse_mass_ = 0;
  double inverse_inertia_ = 0;
};

}  // namespace

std::unique_ptr<Drive> make_planar_drive(const DriveContext& context) {
  return std::make_unique<PlanarDrive>(context);
}

double chassis_origin_height(const RobotTypeConfig& type) {
  return type.model == DriveModel::Jointed ? type.center_of_mass_height : 0.0;
}

void yaw_rotation(double heading, dMatrix3 R) {
  yaw_rotation(std::cos(heading), std::sin(heading), R);
}

void place_chassis(dBodyID chassis, const PlanarState& s, double height) {
  dMatrix3 R;
  yaw_rotation(s.heading, R);
  dBodySetPosition(chassis, s.x, s.y, height);
  dBodySetRotation(chassis, R);
  dBodySetLinearVel(chassis, s.vx, s.vy, 0);
  dBodySetAngularVel(chassis, 0, 0, s.omega);
  dBodySetForce(chassis, 0, 0, 0);
  dBodySetTorque(chassis, 0, 0, 0);
}

Eigen::VectorXd rolling_wheel_speeds(const WheelKinematics& kinematics, const PlanarState& s) {
  const double c = std::cos(s.heading);
  const double sn = std::sin(s.heading);
  return kinematics.wheel_speeds(
      Eigen::Vector3d(c * s.vx + sn * s.vy, -sn * s.vx + c * s.vy, s.omega));
}

void yaw_rotation(double c, double s, dMatrix3 R) {
  R[0] = c;
  R[1] = -s;
  R[2] = 0;
  R[3] = 0;
  R[4] = s;
  R[5] = c;
  R[6] = 0;
  R[7] = 0;
  R[8] = 0;
  R[9] = 0;
  R[10] = 1;
  R[11] = 0;
}

}  // namespace ubersim::physics
