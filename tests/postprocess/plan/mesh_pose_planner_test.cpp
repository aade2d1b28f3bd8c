#include "postprocess/plan/mesh_pose_planner.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "machines/joint_analysis.h"
#include "machines/profile.h"
#include "machines/robot_arm.h"
#include "machines/workpiece_pose.h"
#include "patterns/registry.h"
#include "slicer/input_error.h"
#include "slicer/params.h"
#include "slicer/units.h"
#include "tests/support/mesh_shapes.h"

namespace strand::post {
namespace {

using slicer::Vec2;
using slicer::Vec3;

const Vec3 kCapCentre(-20.0, 0.0, 40.0);  // the sample cap: apex at (20, 0, 40), facing +x

slicer::Toolpath pattern(const std::string& generator, const nlohmann::json& params) {
  const patterns::GeneratorSpec* g = patterns::find_generator(generator);
  return g->generate(slicer::resolve_params(g->table(), params));
}

// The pattern centred on the mesh's (u, v) map, as produce_on_mesh places it.
slicer::Toolpath centred(slicer::Toolpath t, const slicer::MeshSubstrate& s) {
  const auto [lo, hi] = slicer::bounds(t);
  const slicer::UvBox box = s.domain();
  const Vec2 d = (box.min_mm + box.max_mm) / 2.0 - (lo + hi) / 2.0;
  for (auto& l : t.layers) {
    for (auto& st : l.strokes) {
      st.start_mm += d;
      for (auto& seg : st.segments) seg.end_mm += d, seg.center_mm += d;
    }
  }
  return t;
}

machines::RobotCell kuka() { return machines::load_profile("kuka-iiwa14-wasp-cylinder").robot; }

PosePlanOptions options(const machines::RobotCell& c) {
  PosePlanOptions o;
  o.default_deposit_speed_mm_per_s = c.v_cart_mm_per_s;
  o.travel_speed_mm_per_s = o.lift_speed_mm_per_s = c.travel_speed_mm_per_s;
  o.lift_mm = c.lift_mm;
  return o;
}

// Rotation about `up` between two orientations, deg (the twist of b a^T).
double twist_deg(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b, const Vec3& up) {
  return std::abs(slicer::rad_to_deg(rotation_about(b, a, up)));
}

// Everything a program on a mesh promises, for every pose.
void expect_sound(const MeshPlan& plan, const slicer::MeshSubstrate& s,
                  const machines::RobotCell& cell, const slicer::Toolpath& placed) {
  const auto& pts = plan.program.points;
  ASSERT_GT(pts.size(), 100u);
  const Vec3 up = -cell.nozzle_axis;
  double worst_offset = 0.0, worst_normal = 0.0, worst_twist = 0.0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const auto& p = pts[i];
    const Eigen::Matrix3d r = machines::rotation_of(p.workpiece_wxyz);
    // The contact point at the nozzle tip, its normal against the nozzle axis.
    EXPECT_LT((r * p.contact_mm + p.workpiece_origin_mm - cell.nozzle_tip_mm).norm(), 1e-9) << i;
    EXPECT_LT((r * p.normal).cross(up).norm(), 1e-9) << i;
    EXPECT_GT((r * p.normal).dot(up), 0.0) << i;
    // On the layer's offset surface of the mesh (deposits) or above it (travels).
    const auto at = s.locate(p.contact_mm);
    const double layer_offset = placed.layers[static_cast<std::size_t>(p.layer)].z_mm;
    const double off = p.extrude ? std::hypot(at.residual_mm, at.offset_mm - layer_offset)
                                 : std::max(at.residual_mm, layer_offset - at.offset_mm);
    worst_offset = std::max(worst_offset, off);
    worst_normal =
        std::max(worst_normal,
                 slicer::rad_to_deg(std::acos(std::clamp(p.normal.dot(at.normal), -1.0, 1.0))));
    // Within a pass the rotation about the nozzle axis moves continuously (a restart turns in
    // place, the contact point still).
    if (i > 0 && p.lap == pts[i - 1].lap && (p.contact_mm - pts[i - 1].contact_mm).norm() > 1e-9) {
      worst_twist =
          std::max(worst_twist, twist_deg(machines::rotation_of(pts[i - 1].workpiece_wxyz), r, up));
    }
  }
  EXPECT_LT(worst_offset, 0.05);
  EXPECT_LT(worst_normal, 1.0);
  EXPECT_LT(worst_twist, 2.0);
  // The arm: every pose solved, within its limits, and the joints reproduce the poses.
  const machines::ArmModel arm = machines::arm_model(cell);
  const machines::JointReport j = machines::analyse_joints(arm, cell, pts, true);
  EXPECT_TRUE(j.ok()) << j.first_unreachable_what << j.first_outside_what;
  ASSERT_EQ(j.solutions.size(), pts.size());
  double worst_fk_mm = 0.0, worst_fk_deg = 0.0, worst_step = 0.0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Eigen::Isometry3d w =
        machines::forward_kinematics(arm, j.solutions[i]) * machines::workpiece_in_flange(cell);
    const auto& p = pts[i];
    worst_fk_mm = std::max(worst_fk_mm, (w.translation() - p.workpiece_origin_mm).norm());
    const Eigen::AngleAxisd diff(w.linear() * machines::rotation_of(p.workpiece_wxyz).transpose());
    worst_fk_deg = std::max(worst_fk_deg, slicer::rad_to_deg(std::abs(diff.angle())));
    if (i > 0 && (p.contact_mm - pts[i - 1].contact_mm).norm() > 1e-9)
      worst_step =
          std::max(worst_step, (j.solutions[i] - j.solutions[i - 1]).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(worst_fk_mm, 0.01);
  EXPECT_LT(worst_fk_deg, 0.01);
  EXPECT_LT(slicer::rad_to_deg(worst_step), 10.0) << "a joint jumps between neighbouring poses";
}

TEST(MeshPosePlanner, ALatticeOnASphereCap) {
  const auto cell = kuka();
  const slicer::MeshSubstrate s(
      testing::sphere_cap_mesh(kCapCentre, Vec3::UnitX(), 40.0, 50.0, 20, 72), "cap");
  const slicer::Toolpath t =
      centred(pattern("tetrachiral",
                      {{"nozzle", 1.2}, {"cell", 10}, {"cols", 3}, {"rows", 3}, {"layers", 2}}),
              s);
  const MeshPlan plan = plan_poses_on_mesh(t, s, cell, options(cell));
  expect_sound(plan, s, cell, t);
  EXPECT_EQ(plan.program.laps.size(), 2u);  // one pass a layer: the cap is well within reach
  EXPECT_EQ(plan.restarts, 0u);
  EXPECT_GT(plan.max_tilt_deg, 30.0);  // the lattice spans the cap: the workpiece tilts
  EXPECT_EQ(plan.program.substrate.at("kind"), "mesh");
  for (const auto& p : plan.program.points) EXPECT_EQ(p.turn_rad, 0.0);
}

TEST(MeshPosePlanner, AScaffoldOnASaddle) {
  const auto cell = kuka();
  const slicer::MeshSubstrate s(
      testing::saddle_mesh(Vec3(20.0, 0.0, 40.0), Vec3::UnitX(), 50.0, 60.0, 40), "saddle");
  const slicer::Toolpath t = centred(
      pattern("scaffold", {{"nozzle", 1.2}, {"gap", 2.0}, {"size", "30x30"}, {"layers", 3}}), s);
  const MeshPlan plan = plan_poses_on_mesh(t, s, cell, options(cell));
  expect_sound(plan, s, cell, t);
  EXPECT_EQ(plan.program.layers.size(), 3u);
}

TEST(MeshPosePlanner, APassEndsWhereAJointRangeEndsAndRestartsTurned) {
  // The UR10e with its wrist 3 held below 120 deg (the lattice on the cap needs 23..155 deg of
  // it): passes restart turned about the nozzle axis, and the program stays inside the limits.
  auto cell = machines::load_profile("ur10e-wasp-cylinder").robot;
  cell.joint_limits_deg[5] = 120.0;
  cell.motion.home_joints_deg.reset();
  const slicer::MeshSubstrate s(
      testing::sphere_cap_mesh(kCapCentre, Vec3::UnitX(), 40.0, 50.0, 20, 72), "cap");
  const slicer::Toolpath t =
      centred(pattern("tetrachiral",
                      {{"nozzle", 1.2}, {"cell", 10}, {"cols", 3}, {"rows", 3}, {"layers", 1}}),
              s);
  const MeshPlan plan = plan_poses_on_mesh(t, s, cell, options(cell));
  EXPECT_GT(plan.restarts, 0u);
  EXPECT_EQ(plan.program.laps.size(), 1u + plan.restarts);
  expect_sound(plan, s, cell, t);
  // Each restart turns the workpiece in place about the nozzle axis (backed off, nothing
  // deposited) at the end of its pass; the new lap starts at the restart's last row.
  const auto& pts = plan.program.points;
  const Vec3 up = -cell.nozzle_axis;
  for (std::size_t k = 1; k < plan.program.laps.size(); ++k) {
    const auto& lap = plan.program.laps[k];
    EXPECT_FALSE(pts[lap.first].extrude);
    double turned = 0.0;
    for (std::size_t i = plan.program.laps[k - 1].first + 1; i <= lap.first; ++i) {
      if ((pts[i].contact_mm - pts[i - 1].contact_mm).norm() > 1e-9) continue;
      EXPECT_FALSE(pts[i].extrude);
      const double step = twist_deg(machines::rotation_of(pts[i - 1].workpiece_wxyz),
                                    machines::rotation_of(pts[i].workpiece_wxyz), up);
      EXPECT_LE(step, 1.0 + 1e-9);
      turned += step;
    }
    EXPECT_GE(turned, kMeshRotationStepDeg - 1e-6) << "lap " << k;
  }
}

TEST(MeshPosePlanner, AMeshOutOfReachIsRefusedNamingThePoint) {
  auto cell = kuka();
  cell.nozzle_tip_mm = Vec3(1900.0, 0.0, 450.0);  // far beyond the iiwa's 820 mm
  const slicer::MeshSubstrate s(
      testing::sphere_cap_mesh(kCapCentre, Vec3::UnitX(), 40.0, 50.0, 12, 48), "cap.stl");
  const slicer::Toolpath t = centred(
      pattern("scaffold", {{"nozzle", 1.2}, {"gap", 2.0}, {"size", "20x20"}, {"layers", 1}}), s);
  try {
    plan_poses_on_mesh(t, s, cell, options(cell));
    ADD_FAILURE() << "out of reach";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_EQ(
        m.rfind("substrate.mesh = cap.stl: the robot cannot present pattern point (u, v) = (", 0),
        0u)
        << m;
    EXPECT_NE(m.find("nozzle tip at (x, y, z) = ("), std::string::npos) << m;
    EXPECT_NE(m.find("beyond the reach of 820 mm"), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos);
  }
}

TEST(MeshPosePlanner, ATroughThatRisesIntoTheNozzleIsRefused) {
  // The inside of a half pipe, radius 10 mm: printing across it, the far wall enters the
  // nozzle's cone (30 deg, 25 mm).
  const auto cell = kuka();
  const slicer::MeshSubstrate s(
      testing::trough_mesh(Vec3(20.0, 0.0, 40.0), Vec3::UnitX(), 10.0, 60.0, 48, 30), "trough.stl");
  const slicer::Toolpath t = centred(
      pattern("scaffold", {{"nozzle", 1.2}, {"gap", 2.0}, {"size", "26x30"}, {"layers", 1}}), s);
  try {
    plan_poses_on_mesh(t, s, cell, options(cell));
    ADD_FAILURE() << "the trough's wall meets the nozzle";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind("substrate.mesh = trough.stl: the nozzle would touch the mesh at (", 0), 0u)
        << m;
    EXPECT_NE(m.find("with its tip at pattern point (u, v) = ("), std::string::npos) << m;
    EXPECT_NE(m.find("robot.nozzle_cone"), std::string::npos) << m;
  }
  // The same trough with a narrow strip along its bottom is fine.
  const slicer::Toolpath strip = centred(
      pattern("scaffold", {{"nozzle", 1.2}, {"gap", 2.0}, {"size", "6x30"}, {"layers", 1}}), s);
  EXPECT_NO_THROW(plan_poses_on_mesh(strip, s, cell, options(cell)));
}

TEST(MeshPosePlanner, RotationAboutTheNozzleAxisIsTheTwistOfTheRelativeRotation) {
  const Vec3 up = Vec3::UnitZ();
  const Eigen::Matrix3d ref = Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Matrix3d turned = Eigen::AngleAxisd(0.25, up).toRotationMatrix() * ref;
  EXPECT_NEAR(rotation_about(turned, ref, up), 0.25, 1e-12);
  const Eigen::Matrix3d tilted = Eigen::AngleAxisd(0.4, Vec3::UnitX()).toRotationMatrix() * ref;
  EXPECT_NEAR(rotation_about(tilted, ref, up), 0.0, 1e-12);
  // The reference pose puts the mesh's facing against the nozzle.
  const auto cell = kuka();
  const Eigen::Matrix3d r = mesh_reference_rotation(Vec3::UnitX(), cell);
  EXPECT_TRUE((r * Vec3::UnitX()).isApprox(-cell.nozzle_axis, 1e-12));
  EXPECT_TRUE((r * Vec3::UnitZ()).isApprox(cell.substrate_axis, 1e-12));
}

}  // namespace
}  // namespace strand::post
