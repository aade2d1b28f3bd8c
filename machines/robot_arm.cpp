// DH forward kinematics, Jacobian and damped-least-squares inverse kinematics with Eigen.
#include "machines/robot_arm.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "slicer/units.h"

namespace strand::machines {

namespace {

// Converged when the flange is this close to the target (mm and rad): far below the
// 0.01 mm the pose checks ask for.
constexpr double kIkPositionMm = 1e-5;
constexpr double kIkOrientationRad = 1e-8;
// Orientation errors are weighted as if they acted at this lever arm, mm (balances the mm
// and rad rows of the least-squares problem).
constexpr double kOrientationLeverMm = 200.0;
// Damping of the least-squares step, mm: small next to the arm's size, enough near
// singular wrists; it shrinks with the error (Levenberg-Marquardt style), so the last steps
// converge fast even near a singularity.
constexpr double kDampingMm = 1.0;
// Largest joint step per iteration, rad: keeps the solver on one branch.
constexpr double kMaxStepRad = 0.3;
// Joint scale of the least-squares step: the last joint (the workpiece's own axis, clamped
// coaxially) is the cheap way to turn the workpiece, so it takes turns before the arm does.
constexpr double kLastJointScale = 10.0;
// Null-space pull toward mid-range (a gradient step on sum (q / limit)^2), per iteration,
// while the flange is still farther than kNullSpaceMm from the target (mm, orientation at the
// lever arm): the last steps are plain least squares, which converge.
constexpr double kMidRangeGain = 0.05;
constexpr double kNullSpaceMm = 0.05;

Eigen::Isometry3d dh_transform(const DhRow& r, double q) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.rotate(Eigen::AngleAxisd(q, Vec3::UnitZ()));
  t.translate(Vec3(r.a_mm, 0.0, r.d_mm));
  t.rotate(Eigen::AngleAxisd(r.alpha_rad, Vec3::UnitX()));
  return t;
}

// Rotation vector taking `from` onto `to` (both rotations), base frame.
Vec3 rotation_error(const Eigen::Matrix3d& to, const Eigen::Matrix3d& from) {
  const Eigen::AngleAxisd aa(to * from.transpose());
  return aa.axis() * aa.angle();
}

}  // namespace

namespace {

// Joint limits of the cell (upper; lower from joint_min_deg when the profile gives it).
void set_limits(ArmModel& m, const RobotCell& cell) {
  for (int i = 0; i < m.axes; ++i) {
    m.limit_rad[i] = slicer::deg_to_rad(cell.joint_limits_deg[static_cast<std::size_t>(i)]);
    m.limit_min_rad[i] =
        cell.joint_min_deg ? slicer::deg_to_rad((*cell.joint_min_deg)[static_cast<std::size_t>(i)])
                           : -m.limit_rad[i];
  }
  // Unused joints: held at 0, a range that keeps the mid-range pull at 0.
  for (int i = m.axes; i < 7; ++i) m.limit_rad[i] = 1.0, m.limit_min_rad[i] = -1.0;
}

Joints joints_deg(std::initializer_list<double> deg) {
  Joints q = Joints::Zero();
  int i = 0;
  for (double d : deg) q[i++] = slicer::deg_to_rad(d);
  return q;
}

}  // namespace

ArmModel lbr_iiwa_14_r820(const RobotCell& cell) {
  const double h = slicer::kPi / 2.0;
  ArmModel m;
  m.name = "KUKA LBR iiwa 14 R820";
  m.dh = {DhRow{0, -h, 360.0}, DhRow{0, h, 0.0}, DhRow{0, h, 420.0},  DhRow{0, -h, 0.0},
          DhRow{0, -h, 400.0}, DhRow{0, h, 0.0}, DhRow{0, 0.0, 126.0}};
  set_limits(m, cell);
  m.shoulder_mm = Vec3(0.0, 0.0, 360.0);
  m.reach_mm = cell.reach_mm;
  m.flange_mm = 126.0;
  for (double a2 : {30.0, 60.0})
    for (double a4 : {-60.0, -90.0, 60.0, 90.0})
      for (double a6 : {-60.0, 60.0}) m.seeds.push_back(joints_deg({0, a2, 0, a4, 0, a6, 0}));
  return m;
}

ArmModel ur10e(const RobotCell& cell) {
  const double h = slicer::kPi / 2.0;
  ArmModel m;
  m.name = "Universal Robots UR10e";
  m.axes = 6;
  m.dh = {DhRow{0, h, 180.7},   DhRow{-612.7, 0, 0.0}, DhRow{-571.55, 0, 0.0}, DhRow{0, h, 174.15},
          DhRow{0, -h, 119.85}, DhRow{0, 0, 116.55},   DhRow{0, 0, 0}};
  set_limits(m, cell);
  m.shoulder_mm = Vec3(0.0, 0.0, 180.7);
  m.reach_mm = cell.reach_mm;
  m.flange_mm = 116.55;
  for (double base : {0.0, 180.0})
    for (double elbow : {90.0, -90.0})
      for (double wrist2 : {90.0, -90.0})
        m.seeds.push_back(
            joints_deg({base, -90.0 - elbow / 2, elbow, -90.0 - elbow / 2, wrist2, 0}));
  return m;
}

ArmModel irb1200_5_09(const RobotCell& cell) {
  const double h = slicer::kPi / 2.0;
  ArmModel m;
  m.name = "ABB IRB 1200-5/0.9";
  m.axes = 6;
  m.dh = {DhRow{0, -h, 399.0}, DhRow{448.0, 0, 0.0}, DhRow{42.0, -h, 0.0}, DhRow{0, h, 451.0},
          DhRow{0, -h, 0.0},   DhRow{0, 0, 82.0},    DhRow{0, 0, 0}};
  m.offset_rad[1] = -h;
  m.offset_rad[5] = slicer::kPi;
  set_limits(m, cell);
  m.shoulder_mm = Vec3(0.0, 0.0, 399.0);
  m.reach_mm = cell.reach_mm;
  m.flange_mm = 82.0;
  for (double a2 : {0.0, 30.0})
    for (double a3 : {0.0, -30.0})
      for (double a5 : {45.0, -45.0}) m.seeds.push_back(joints_deg({0, a2, a3, 0, a5, 0}));
  return m;
}

ArmModel arm_model(const RobotCell& cell) {
  if (cell.arm == "ur10e") return ur10e(cell);
  if (cell.arm == "irb1200-5-0.9") return irb1200_5_09(cell);
  return lbr_iiwa_14_r820(cell);
}

bool within_limits(const ArmModel& arm, const Joints& q, double slack) {
  for (int i = 0; i < arm.axes; ++i)
    if (q[i] > arm.limit_rad[i] + slack || q[i] < arm.limit_min_rad[i] - slack) return false;
  return true;
}

Eigen::Isometry3d forward_kinematics(const ArmModel& arm, const Joints& q) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  for (int i = 0; i < arm.axes; ++i) t = t * dh_transform(arm.dh[i], q[i] + arm.offset_rad[i]);
  return t;
}

Eigen::Matrix<double, 6, 7> jacobian(const ArmModel& arm, const Joints& q) {
  std::array<Eigen::Isometry3d, 8> frames;
  frames[0] = Eigen::Isometry3d::Identity();
  for (int i = 0; i < arm.axes; ++i)
    frames[i + 1] = frames[i] * dh_transform(arm.dh[i], q[i] + arm.offset_rad[i]);
  const Vec3 end = frames[arm.axes].translation();
  Eigen::Matrix<double, 6, 7> j = Eigen::Matrix<double, 6, 7>::Zero();
  for (int i = 0; i < arm.axes; ++i) {
    const Vec3 z = frames[i].linear().col(2);
    j.block<3, 1>(0, i) = z.cross(end - frames[i].translation());
    j.block<3, 1>(3, i) = z;
  }
  return j;
}

Vec3 wrist_centre(const ArmModel& arm, const Eigen::Isometry3d& flange) {
  return flange.translation() - arm.flange_mm * flange.linear().col(2);
}

IkResult solve_ik(const ArmModel& arm, const Eigen::Isometry3d& target, const Joints& seed,
                  int max_iterations) {
  using Mat67 = Eigen::Matrix<double, 6, 7>;
  using Mat76 = Eigen::Matrix<double, 7, 6>;
  using Mat6 = Eigen::Matrix<double, 6, 6>;
  Joints scale = Joints::Ones();
  scale[arm.axes - 1] = kLastJointScale;
  for (int i = arm.axes; i < 7; ++i) scale[i] = 0.0;  // unused joints stay where they are
  const Joints mid = (arm.limit_rad + arm.limit_min_rad) / 2.0;
  const Joints half = (arm.limit_rad - arm.limit_min_rad) / 2.0;
  IkResult r;
  r.q = seed;
  for (r.iterations = 0; r.iterations <= max_iterations; ++r.iterations) {
    const Eigen::Isometry3d t = forward_kinematics(arm, r.q);
    const Vec3 ep = target.translation() - t.translation();
    const Vec3 eo = rotation_error(target.linear(), t.linear());
    r.position_error_mm = ep.norm();
    r.orientation_error_rad = eo.norm();
    if (r.position_error_mm < kIkPositionMm && r.orientation_error_rad < kIkOrientationRad) {
      r.converged = true;
      break;
    }
    if (r.iterations == max_iterations) break;
    // Work in scaled joints x = q / scale: J_s = J diag(scale).
    Mat67 j = jacobian(arm, r.q) * scale.asDiagonal();
    j.bottomRows<3>() *= kOrientationLeverMm;
    Eigen::Matrix<double, 6, 1> e;
    e << ep, kOrientationLeverMm * eo;
    const Mat6 jjt = j * j.transpose();
    const double lambda = kDampingMm * std::min(1.0, e.norm() / kDampingMm);
    const Mat76 damped = j.transpose() * (jjt + lambda * lambda * Mat6::Identity()).inverse();
    Joints dq = damped * e;
    if (e.norm() > kNullSpaceMm) {
      // The undamped projector keeps the mid-range pull out of the task exactly.
      const Mat76 exact = j.transpose() * jjt.completeOrthogonalDecomposition().pseudoInverse();
      const Joints gradient = (r.q - mid).cwiseQuotient(half.cwiseAbs2()).cwiseProduct(scale);
      dq -= kMidRangeGain * (Eigen::Matrix<double, 7, 7>::Identity() - exact * j) * gradient;
    }
    dq = dq.cwiseProduct(scale);
    const double biggest = dq.cwiseAbs().maxCoeff();
    if (biggest > kMaxStepRad) dq *= kMaxStepRad / biggest;
    r.q += dq;
  }
  return r;
}

}  // namespace strand::machines
