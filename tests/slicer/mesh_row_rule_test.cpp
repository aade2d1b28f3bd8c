#include "slicer/mesh_row_rule.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>

#include "slicer/mesh_io.h"
#include "slicer/units.h"

namespace strand::slicer {
namespace {

// Public meshes cut to open patches (tests/data/README.md), placed for a robot to hold.
std::string data(const std::string& name) {
  return std::string(STRAND_SOURCE_DIR) + "/tests/data/" + name;
}

MeshSubstrate substrate(const std::string& name) {
  return MeshSubstrate(read_mesh_file(data(name)), name);
}

// Pattern points on a grid over the (u, v) map's box, `cells` per side, those on the map.
std::vector<Vec2> grid(const MeshSubstrate& s, int cells) {
  const UvBox b = s.domain();
  const Vec2 c = (b.min_mm + b.max_mm) / 2.0, h = (b.max_mm - b.min_mm) / 2.0;
  std::vector<Vec2> out;
  for (int i = 0; i <= cells; ++i)
    for (int j = 0; j <= cells; ++j) {
      const Vec2 uv = c + Vec2(h.x() * (2.0 * i / cells - 1.0), h.y() * (2.0 * j / cells - 1.0));
      if (s.in_domain(uv)) out.push_back(uv);
    }
  return out;
}

// On the coarse bunny patch, S + o N alone comes closer to the faceted mesh than o; the rule's
// rows are o from it, and read back to their own foot and normal.
TEST(MeshRowRule, RowsAreTheirOffsetFromACoarseConcaveMesh) {
  const MeshSubstrate s = substrate("bunny-patch.obj");
  double worst_plain = 0.0;
  for (const Vec2& uv : grid(s, 24)) {
    for (const double o : {0.704, 1.408, 2.112}) {
      worst_plain = std::max(worst_plain, o - s.distance_mm(s.frame_at(uv, o).point_mm));
      const SurfaceFrame f = mesh_row_frame(s, uv, o);
      const MeshRowReading r = read_mesh_row(s, f.point_mm, f.normal);
      ASSERT_TRUE(r.over_mesh);
      EXPECT_NEAR(r.clearance_mm, o, 1e-3) << uv.transpose();
      EXPECT_GE(r.along_mm, o - 1e-9);
      EXPECT_LT(r.normal_off_deg, 1e-3);
      EXPECT_LT((r.uv_mm - uv).norm(), 1e-6);
    }
  }
  EXPECT_GT(worst_plain, kMeshSurfaceMm) << "the case the rule is for";
}

// A restart's lift and turn in place, far above a concave bunny patch: read back along the
// normal, not from the mesh's nearest point, the row keeps its own foot.
TEST(MeshRowRule, ALiftedRowReadsBackToItsOwnFoot) {
  const MeshSubstrate s = substrate("bunny-patch.obj");
  double worst_nearest_deg = 0.0;
  for (const Vec2& uv : grid(s, 16)) {
    const SurfaceFrame f = mesh_row_frame(s, uv, 1.408 + 3.0);
    const MeshRowReading r = read_mesh_row(s, f.point_mm, f.normal);
    ASSERT_TRUE(r.over_mesh);
    EXPECT_LT(r.normal_off_deg, 1e-3);
    EXPECT_GE(r.clearance_mm, 1.408 + 3.0 - 1e-3);
    const double cosine = std::clamp(s.locate(f.point_mm).normal.dot(f.normal), -1.0, 1.0);
    worst_nearest_deg = std::max(worst_nearest_deg, rad_to_deg(std::acos(cosine)));
  }
  // Mapped back from the mesh's nearest points instead (the check before the rule), rows this
  // high above concave facets land on another foot.
  EXPECT_GT(worst_nearest_deg, kMeshNormalDeg);
}

TEST(MeshRowRule, JudgesDepositsTravelsAndNormals) {
  const MeshSubstrate s = substrate("saddle-patch.obj");
  const Vec2 uv = (s.domain().min_mm + s.domain().max_mm) / 2.0;
  const SurfaceFrame f = mesh_row_frame(s, uv, 1.0);
  std::vector<PosePoint> rows(4);
  for (auto& p : rows) p.contact_mm = f.point_mm, p.normal = f.normal;
  rows[1].extrude = rows[2].extrude = true;
  rows[2].contact_mm += 0.2 * f.normal;  // a deposit off its layer
  rows[3].contact_mm -= 0.5 * f.normal;  // a travel under it
  rows[0].normal = Eigen::AngleAxisd(0.05, f.d_du.normalized()) * f.normal;  // 2.9 deg
  std::vector<MeshRowReading> at;
  for (const auto& p : rows) at.push_back(read_mesh_row(s, p.contact_mm, p.normal));
  const MeshRowJudgement j = judge_mesh_rows(rows, at, {1.0});
  ASSERT_EQ(j.normals.size(), 1u);
  EXPECT_EQ(j.normals[0].row, 0u);
  EXPECT_NE(j.normals[0].what.find("off the mesh's normal"), std::string::npos);
  ASSERT_EQ(j.off_surface.size(), 2u);
  EXPECT_EQ(j.off_surface[0].row, 2u);
  EXPECT_NE(j.off_surface[0].what.find("mm off layer 0's offset surface"), std::string::npos);
  EXPECT_EQ(j.off_surface[1].row, 3u);
  EXPECT_NEAR(j.worst_deposit_mm, 0.2, 1e-3);
  EXPECT_EQ(j.worst_deposit_row, 2u);
}

}  // namespace
}  // namespace strand::slicer
