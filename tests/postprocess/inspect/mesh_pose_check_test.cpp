#include "postprocess/inspect/mesh_pose_check.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "machines/pose_csv.h"
#include "machines/profile.h"
#include "machines/workpiece_pose.h"
#include "patterns/registry.h"
#include "postprocess/plan/mesh_pose_planner.h"
#include "slicer/file_io.h"
#include "slicer/json_input.h"
#include "slicer/mesh_io.h"
#include "slicer/params.h"
#include "slicer/units.h"
#include "tests/support/cli_runner.h"
#include "tests/support/mesh_shapes.h"

namespace strand::post {
namespace {

using slicer::Vec2;
using slicer::Vec3;

// A saddle the iiwa holds, a two-layer scaffold planned on it, its CSV and record in `dir`.
struct Planned {
  std::string dir, csv_path, csv;
  machines::MachineProfile machine = machines::load_profile("kuka-iiwa14-wasp-cylinder");
  slicer::PoseProgram program;
};

Planned plan_saddle() {
  Planned p;
  p.dir = testing::fresh_dir("mesh-check");
  const std::string mesh = p.dir + "/saddle.stl";
  testing::write_binary_stl(
      testing::saddle_mesh(Vec3(20.0, 0.0, 40.0), Vec3::UnitX(), 50.0, 60.0, 40), mesh);
  const slicer::MeshSubstrate s(slicer::read_mesh_file(mesh), mesh);
  const patterns::GeneratorSpec* g = patterns::find_generator("scaffold");
  slicer::Toolpath t = g->generate(slicer::resolve_params(
      g->table(), {{"nozzle", 1.2}, {"gap", 2.0}, {"size", "24x24"}, {"layers", 2}}));
  const auto [lo, hi] = slicer::bounds(t);
  const Vec2 d = (s.domain().min_mm + s.domain().max_mm) / 2.0 - (lo + hi) / 2.0;
  for (auto& l : t.layers) {
    for (auto& st : l.strokes) {
      st.start_mm += d;
      for (auto& seg : st.segments) seg.end_mm += d, seg.center_mm += d;
    }
  }
  PosePlanOptions o;
  const auto& c = p.machine.robot;
  o.default_deposit_speed_mm_per_s = c.v_cart_mm_per_s;
  o.travel_speed_mm_per_s = o.lift_speed_mm_per_s = c.travel_speed_mm_per_s;
  o.lift_mm = c.lift_mm;
  p.program = plan_poses_on_mesh(t, s, c, o).program;
  p.csv = machines::write_pose_csv(p.program);
  p.csv_path = p.dir + "/part.csv";
  slicer::write_file_atomic(p.csv_path, p.csv);
  slicer::MeshSubstrateRecord r;
  r.mesh = "saddle.stl";
  r.fingerprint = slicer::content_fingerprint(slicer::read_file(mesh));
  r.machine = p.machine.name;
  for (const auto& l : p.program.layers) r.layer_offsets_mm.push_back(l.offset_mm);
  slicer::write_file_atomic(slicer::mesh_record_path(p.csv_path),
                            slicer::dump_json(slicer::to_json(r)));
  return p;
}

// The first deposit row past the middle of the program.
std::size_t a_deposit(const slicer::PoseProgram& p) {
  for (std::size_t i = p.points.size() / 2; i < p.points.size(); ++i)
    if (p.points[i].extrude && p.points[i - 1].extrude) return i;
  return 0;
}

PoseCheckReport check(const Planned& p, const std::string& csv) {
  const auto mesh = find_csv_mesh(p.csv_path, "");
  EXPECT_TRUE(mesh.has_value());
  return check_mesh_pose_csv(csv, p.csv_path, p.machine, *mesh);
}

TEST(MeshPoseCheck, APlannedProgramChecksCleanOnItsMesh) {
  const Planned p = plan_saddle();
  const auto mesh = find_csv_mesh(p.csv_path, "");
  ASSERT_TRUE(mesh.has_value());
  EXPECT_EQ(mesh->mesh_path, p.dir + "/saddle.stl");  // from the record, beside the CSV
  const PoseCheckReport r = check(p, p.csv);
  EXPECT_TRUE(r.ok()) << to_text(r);
  EXPECT_TRUE(r.on_mesh);
  ASSERT_EQ(r.layers.size(), 2u);
  EXPECT_NEAR(r.layers[0].radius_mm, p.program.layers[0].offset_mm, 1e-3);  // the offset
  EXPECT_GT(r.layers[0].strands, 0);
  EXPECT_NE(to_text(r).find("layer  offset_mm"), std::string::npos);
  // No record and no mesh given: not a mesh CSV.
  EXPECT_FALSE(find_csv_mesh(p.dir + "/other.csv", "").has_value());
}

// A contact point moved 0.2 mm along its normal, the workpiece moved with it so the nozzle tip
// still matches: only the mesh says the deposit is off its layer.
TEST(MeshPoseCheck, ADepositOffItsOffsetSurfaceIsFoundByItsRow) {
  Planned p = plan_saddle();
  const std::size_t i = a_deposit(p.program);
  auto& pt = p.program.points[i];
  const Eigen::Matrix3d r = machines::rotation_of(pt.workpiece_wxyz);
  pt.contact_mm += 0.2 * pt.normal;
  pt.workpiece_origin_mm -= r * (0.2 * pt.normal);
  const PoseCheckReport rep = check(p, machines::write_pose_csv(p.program));
  EXPECT_FALSE(rep.ok());
  EXPECT_EQ(rep.off_tip.total, 0u) << to_text(rep);
  ASSERT_GE(rep.off_surface.total, 1u);
  EXPECT_EQ(rep.off_surface.listed.front().row, i);
  EXPECT_NE(rep.off_surface.listed.front().what.find("mm off layer"), std::string::npos);
}

TEST(MeshPoseCheck, ANormalThatIsNotTheMeshsIsFound) {
  Planned p = plan_saddle();
  const std::size_t i = a_deposit(p.program);
  auto& pt = p.program.points[i];
  // Turn the normal and the workpiece together by 2 deg about a tangent, the contact point
  // kept: the nozzle check still holds, the mesh's normal does not.
  const Vec3 axis = pt.normal.cross(Vec3::UnitZ()).normalized();
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(slicer::deg_to_rad(2.0), axis).toRotationMatrix();
  const Eigen::Matrix3d r = machines::rotation_of(pt.workpiece_wxyz) * turn.transpose();
  pt.normal = turn * pt.normal;
  pt.workpiece_wxyz = machines::quaternion_wxyz(r);
  pt.workpiece_origin_mm = p.machine.robot.nozzle_tip_mm - r * pt.contact_mm;
  const PoseCheckReport rep = check(p, machines::write_pose_csv(p.program));
  EXPECT_EQ(rep.off_tip.total, 0u) << to_text(rep);
  EXPECT_EQ(rep.off_surface.total, 0u) << to_text(rep);
  ASSERT_GE(rep.normals.total, 1u) << to_text(rep);
  EXPECT_EQ(rep.normals.listed.front().row, i);
  EXPECT_NE(rep.normals.listed.front().what.find("off the mesh's normal"), std::string::npos);
}

TEST(MeshPoseCheck, AnotherMeshThanPlannedIsReported) {
  const Planned p = plan_saddle();
  // The same saddle, a little flatter: the record's fingerprint no longer matches, and the
  // contact points leave the offset surfaces.
  testing::write_binary_stl(
      testing::saddle_mesh(Vec3(20.0, 0.0, 40.0), Vec3::UnitX(), 50.0, 70.0, 40),
      p.dir + "/saddle.stl");
  const PoseCheckReport rep = check(p, p.csv);
  EXPECT_FALSE(rep.ok());
  ASSERT_GE(rep.parse.total, 1u);
  EXPECT_NE(rep.parse.listed.front().what.find("is not the one the program was planned on"),
            std::string::npos);
  EXPECT_GT(rep.off_surface.total, 0u);
}

}  // namespace
}  // namespace strand::post
