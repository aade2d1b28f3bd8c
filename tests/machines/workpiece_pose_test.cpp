#include "machines/workpiece_pose.h"

#include <gtest/gtest.h>

#include <random>

#include "slicer/cylinder_surface.h"
#include "slicer/units.h"

namespace strand::machines {
namespace {

TEST(WorkpiecePose, TopOfTheCylinderHandComputed) {
  // Robot cell: tip (800, 0, 450), flow straight down, cylinder axis along +x. The contact
  // at turn 0 is on the workpiece x axis, 20.96 mm out and 30 mm along: the workpiece x axis
  // must point up and its origin sit 20.96 mm under the tip and 30 mm behind it along x.
  const MachineProfile m = load_profile("kuka-iiwa14-wasp-cylinder");
  const WorkpiecePose w = workpiece_pose(holder_of(m), Vec3(20.96, 0.0, 30.0), 0.0);
  EXPECT_NEAR((w.rotation.col(0) - Vec3::UnitZ()).norm(), 0.0, 1e-15);
  EXPECT_NEAR((w.rotation.col(2) - Vec3::UnitX()).norm(), 0.0, 1e-15);
  EXPECT_NEAR((w.origin_mm - Vec3(770.0, 0.0, 429.04)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((w.tip_mm - Vec3(800.0, 0.0, 450.0)).norm(), 0.0, 1e-12);
}

TEST(WorkpiecePose, QuarterTurnTurnsTheWorkpieceBackAboutItsAxis) {
  // The contact at 90 deg around (+y of the workpiece) reaches the nozzle when the workpiece
  // has turned -90 deg about its axis: its y axis then points up.
  const MachineProfile m = load_profile("kuka-iiwa14-wasp-cylinder");
  const WorkpiecePose w = workpiece_pose(holder_of(m), Vec3(0.0, 20.0, 10.0), slicer::kPi / 2);
  EXPECT_NEAR((w.rotation * Vec3::UnitY() - Vec3::UnitZ()).norm(), 0.0, 1e-12);
  EXPECT_NEAR((w.rotation * Vec3(0.0, 20.0, 10.0) + w.origin_mm - w.tip_mm).norm(), 0.0, 1e-12);
}

TEST(WorkpiecePose, EveryContactMeetsTheNozzleAgainstItsAxis) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const slicer::CylinderSurface c({15.0, 60.0});
  for (const char* name : {"kuka-iiwa14-wasp-cylinder", "marlin-rotary-a"}) {
    const MachineProfile m = load_profile(name);
    const Holder h = holder_of(m);
    for (int k = 0; k < 200; ++k) {
      const double turn = 4.0 * u(rng), v = 30.0 + 30.0 * u(rng), off = 1.0 + u(rng);
      const auto f = c.frame_at_turn(turn, v, off);
      const WorkpiecePose w = workpiece_pose(h, f.point_mm, turn);
      EXPECT_NEAR((w.rotation * f.point_mm + w.origin_mm - w.tip_mm).norm(), 0.0, 1e-9);
      EXPECT_NEAR((w.rotation * f.normal + h.nozzle_axis).norm(), 0.0, 1e-12)
          << "normal against the flow";
      EXPECT_NEAR((w.rotation * Vec3::UnitZ() - h.axis_dir).norm(), 0.0, 1e-12)
          << "axis keeps its direction";
    }
  }
}

TEST(WorkpiecePose, QuaternionsRoundTrip) {
  const Eigen::Matrix3d r =
      Eigen::AngleAxisd(2.5, Vec3(1, -2, 0.5).normalized()).toRotationMatrix();
  const auto q = quaternion_wxyz(r);
  EXPECT_NEAR(q.norm(), 1.0, 1e-15);
  EXPECT_GE(q[0], 0.0);
  EXPECT_NEAR((rotation_of(q) - r).norm(), 0.0, 1e-14);
}

}  // namespace
}  // namespace strand::machines
