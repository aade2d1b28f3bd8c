#include "machines/robot_arm.h"

#include <gtest/gtest.h>

#include <random>

#include "machines/joint_analysis.h"
#include "machines/profile.h"
#include "machines/workpiece_pose.h"
#include "slicer/cylinder_surface.h"
#include "slicer/units.h"

namespace strand::machines {
namespace {

const MachineProfile& cell() {
  static const MachineProfile m = load_profile("kuka-iiwa14-wasp-cylinder");
  return m;
}

TEST(RobotArm, StraightUpTheFlangeIs1306mmHigh) {
  // The thesis' table: flange up to 1306 mm = 360 + 420 + 400 + 126.
  const auto arm = lbr_iiwa_14_r820(cell().robot);
  const Eigen::Isometry3d f = forward_kinematics(arm, Joints::Zero());
  EXPECT_NEAR((f.translation() - Vec3(0, 0, 1306)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((f.linear() - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-12);
}

TEST(RobotArm, ElbowAtNinetyDegreesPutsTheForearmLevel) {
  // A4 = 90 deg (A2 = 0): the upper arm is vertical to 780 mm, then the forearm and flange
  // lie in a horizontal line 400 + 126 mm long.
  Joints q = Joints::Zero();
  q[3] = slicer::kPi / 2;
  const Vec3 p = forward_kinematics(lbr_iiwa_14_r820(cell().robot), q).translation();
  EXPECT_NEAR(p.z(), 780.0, 1e-9);
  EXPECT_NEAR(p.head<2>().norm(), 526.0, 1e-9);
}

TEST(RobotArm, JacobianMatchesFiniteDifferences) {
  const auto arm = lbr_iiwa_14_r820(cell().robot);
  Joints q;
  q << 0.3, 0.7, -0.4, -1.2, 0.5, 0.9, -0.2;
  const auto j = jacobian(arm, q);
  const double h = 1e-6;
  for (int i = 0; i < 7; ++i) {
    Joints a = q, b = q;
    a[i] += h, b[i] -= h;
    const Vec3 dp =
        (forward_kinematics(arm, a).translation() - forward_kinematics(arm, b).translation()) /
        (2 * h);
    EXPECT_NEAR((dp - j.block<3, 1>(0, i)).norm(), 0.0, 1e-4) << "joint " << i;
  }
}

TEST(RobotArm, InverseKinematicsReproducesReachablePoses) {
  const auto arm = lbr_iiwa_14_r820(cell().robot);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    Joints q;
    for (int i = 0; i < 7; ++i) q[i] = 0.8 * arm.limit_rad[i] * u(rng);
    const Eigen::Isometry3d target = forward_kinematics(arm, q);
    Joints seed = q;
    for (int i = 0; i < 7; ++i) seed[i] += 0.05 * u(rng);  // a nearby previous pose
    const IkResult r = solve_ik(arm, target, seed);
    ASSERT_TRUE(r.converged) << "trial " << trial << " error " << r.position_error_mm << " mm "
                             << r.orientation_error_rad << " rad after " << r.iterations;
    const Eigen::Isometry3d back = forward_kinematics(arm, r.q);
    EXPECT_LT((back.translation() - target.translation()).norm(), 1e-4);
    EXPECT_LT(Eigen::AngleAxisd(back.linear().transpose() * target.linear()).angle(), 1e-7);
  }
}

// The thesis cell holding a cylinder: a turn sweep of the contact line.
std::vector<slicer::PosePoint> turn_sweep(double from_deg, double to_deg) {
  const slicer::CylinderSurface c({20.0, 80.0});
  const Holder h = holder_of(cell());
  std::vector<slicer::PosePoint> pts;
  for (double d = from_deg; d <= to_deg + 1e-9; d += 2.0) {
    const double turn = slicer::deg_to_rad(d);
    const auto f = c.frame_at_turn(turn, 40.0, 0.96);
    const WorkpiecePose w = workpiece_pose(h, f.point_mm, turn);
    slicer::PosePoint p;
    p.turn_rad = turn;
    p.workpiece_origin_mm = w.origin_mm;
    p.workpiece_wxyz = quaternion_wxyz(w.rotation);
    pts.push_back(p);
  }
  return pts;
}

TEST(JointAnalysis, SolvedJointsReproduceEveryPoseAndTheTurnIsMostlyA7) {
  const auto arm = lbr_iiwa_14_r820(cell().robot);
  const auto pts = turn_sweep(-150, 150);
  const JointReport r = analyse_joints(arm, cell().robot, pts, true);
  ASSERT_TRUE(r.ok()) << r.first_unreachable_what << r.first_outside_what;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Eigen::Isometry3d want =
        flange_pose(cell().robot, pts[i].workpiece_origin_mm, pts[i].workpiece_wxyz);
    const Eigen::Isometry3d got = forward_kinematics(arm, r.solutions[i]);
    EXPECT_LT((got.translation() - want.translation()).norm(), 1e-3) << i;
  }
  // The cylinder is clamped coaxially with A7, so A7 carries most of a 300 deg turn, within
  // its limit; the arm's redundancy takes the rest toward mid-range.
  const double a7 = slicer::rad_to_deg(r.max_rad[6] - r.min_rad[6]);
  EXPECT_GT(a7, 150.0);
  EXPECT_LT(slicer::rad_to_deg(r.max_rad.cwiseAbs().maxCoeff()), 175.0);
}

TEST(JointAnalysis, APoseBeyondTheReachIsNamed) {
  auto pts = turn_sweep(0, 0);
  pts[0].workpiece_origin_mm += Vec3(600.0, 0.0, 0.0);
  const JointReport r = analyse_joints(lbr_iiwa_14_r820(cell().robot), cell().robot, pts);
  EXPECT_EQ(r.unreachable, 1u);
  EXPECT_NE(r.first_unreachable_what.find("> reach 820 mm"), std::string::npos)
      << r.first_unreachable_what;
}

}  // namespace
}  // namespace strand::machines
