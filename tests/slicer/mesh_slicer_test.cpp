// Slices of shapes with known sections: a cube's square, a cylinder's circle, a torus's
// two circles and a bored cylinder's hole, within 0.01 mm of the analytic contour.
#include "slicer/mesh_slicer.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "slicer/mesh_check.h"
#include "slicer/units.h"
#include "tests/support/mesh_shapes.h"

namespace strand::slicer {
namespace {

constexpr double kContourTolMm = 0.01;

// Largest distance from a contour vertex, and from each edge midpoint, to the circle.
double worst_circle_error(const Ring& ring, double radius) {
  double worst = 0.0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Vec2 mid = (ring[i] + ring[(i + 1) % ring.size()]) / 2.0;
    worst = std::max({worst, std::abs(ring[i].norm() - radius), std::abs(mid.norm() - radius)});
  }
  return worst;
}

TEST(MeshSlicer, CubeGivesItsSquareAtEveryHeight) {
  const MeshSlicer s(testing::box_mesh(Vec3(10, 20, 30)));
  for (double z : {0.25, 15.0, 29.75}) {
    const auto contours = slice_at(s, z);
    ASSERT_EQ(contours.size(), 1u) << z;
    EXPECT_NEAR(std::abs(signed_area_mm2(contours[0])), 200.0, 1e-9);
    for (const Vec2& p : contours[0]) {
      const double to_edge =
          std::min({std::abs(p.x()), std::abs(p.x() - 10), std::abs(p.y()), std::abs(p.y() - 20)});
      EXPECT_LT(to_edge, 1e-9);
    }
  }
}

TEST(MeshSlicer, CylinderGivesItsCircle) {
  const MeshSlicer s(testing::tube_mesh(10.0, 0.0, 5.0, 720));
  const auto contours = slice_at(s, 2.5);
  ASSERT_EQ(contours.size(), 1u);
  EXPECT_LT(worst_circle_error(contours[0], 10.0), kContourTolMm);
}

TEST(MeshSlicer, PlaneThroughVerticesStillGivesOneClosedContour) {
  const MeshSlicer s(testing::box_mesh(Vec3(4, 4, 4)));
  EXPECT_EQ(slice_at(s, 4.0 - 1e-12).size(), 1u);
  EXPECT_EQ(slice_at(s, 0.0).size(), 1u) << "moved just above the bottom face";
}

TEST(MeshSlicer, TorusGivesItsTwoCircles) {
  const double R = 20.0, r = 5.0;
  const MeshSlicer s(testing::torus_mesh(R, r, 512, 256));
  for (double z : {1.0, 5.0, 8.5}) {
    const double half = std::sqrt(r * r - (z - r) * (z - r));
    const Region region = region_from_contours(slice_at(s, z));
    ASSERT_EQ(region.size(), 1u) << z;
    ASSERT_EQ(region[0].holes.size(), 1u) << "the torus' hole";
    EXPECT_LT(worst_circle_error(region[0].outer, R + half), kContourTolMm) << z;
    EXPECT_LT(worst_circle_error(region[0].holes[0], R - half), kContourTolMm) << z;
  }
}

TEST(MeshSlicer, BoredCylinderSlicesToARegionWithAHole) {
  const auto layers = slice_layers(testing::tube_mesh(10, 3, 2, 256), 0.5, 4);
  ASSERT_EQ(layers.size(), 4u);
  for (const Region& r : layers) {
    ASSERT_EQ(r.size(), 1u);
    ASSERT_EQ(r[0].holes.size(), 1u);
    EXPECT_GT(signed_area_mm2(r[0].outer), 0.0) << "outer counter-clockwise";
    EXPECT_LT(signed_area_mm2(r[0].holes[0]), 0.0) << "hole clockwise";
    EXPECT_NEAR(area_mm2(r), kPi * (100 - 9), 0.05 * kPi * 100 / 256);
    EXPECT_FALSE(contains(r, Vec2(0, 0)));
    EXPECT_TRUE(contains(r, Vec2(6, 0)));
  }
}

Region rect_region(double x0, double y0, double x1, double y1) {
  return region_from_contours({{Vec2(x0, y0), Vec2(x1, y0), Vec2(x1, y1), Vec2(x0, y1)}});
}

// Area where the two regions differ (symmetric difference), mm^2.
double differ_mm2(const Region& a, const Region& b) {
  return area_mm2(region_difference(a, b)) + area_mm2(region_difference(b, a));
}

// Largest distance from a vertex of `r` to the boundary of the axis-aligned rectangle union
// `rects`: every vertex must lie on some rectangle's edge.
double off_boundary_mm(const Region& r, const std::vector<std::array<double, 4>>& rects) {
  double worst = 0.0;
  for (const Ring& ring : rings_of(r)) {
    for (const Vec2& p : ring) {
      double best = 1e9;
      for (const auto& [x0, y0, x1, y1] : rects) {
        const bool in_x = p.x() >= x0 - 1e-9 && p.x() <= x1 + 1e-9;
        const bool in_y = p.y() >= y0 - 1e-9 && p.y() <= y1 + 1e-9;
        if (in_y) best = std::min({best, std::abs(p.x() - x0), std::abs(p.x() - x1)});
        if (in_x) best = std::min({best, std::abs(p.y() - y0), std::abs(p.y() - y1)});
      }
      worst = std::max(worst, best);
    }
  }
  return worst;
}

TEST(MeshSlicer, TwoOverlappingCubesInOneSoupGiveTheirUnion) {
  const Mesh soup = testing::with_shell(testing::box_mesh(Vec3(10, 10, 10)),
                                        testing::box_mesh(Vec3(10, 10, 10)), Vec3(5, 5, 2));
  ASSERT_GT(check_mesh(soup).self_intersections, 0u) << "the soup does cut itself";
  const auto layers = slice_layers(soup, 1.0, 12);
  ASSERT_EQ(layers.size(), 12u);
  for (int k = 0; k < 12; ++k) {
    const double z = k + 0.5;
    std::vector<std::array<double, 4>> rects;
    if (z < 10) rects.push_back({0, 0, 10, 10});
    if (z > 2) rects.push_back({5, 5, 15, 15});
    Region analytic;
    std::vector<Ring> loops;
    for (const auto& [x0, y0, x1, y1] : rects)
      loops.push_back({Vec2(x0, y0), Vec2(x1, y0), Vec2(x1, y1), Vec2(x0, y1)});
    analytic = region_from_oriented_loops(loops);
    const Region& got = layers[static_cast<std::size_t>(k)];
    ASSERT_EQ(got.size(), 1u) << "one piece at z " << z;
    EXPECT_TRUE(got[0].holes.empty()) << "no hole where the shells overlap, z " << z;
    EXPECT_NEAR(area_mm2(got), z > 2 && z < 10 ? 175.0 : 100.0, 1e-6) << z;
    EXPECT_LT(differ_mm2(got, analytic), 1e-4) << z;
    EXPECT_LT(off_boundary_mm(got, rects), kContourTolMm) << z;
  }
}

// A clean 10 mm cube and four damaged copies: each slices to the same square.
TEST(MeshSlicer, DamagedCubesSliceLikeTheCleanCube) {
  const Mesh clean = testing::box_mesh(Vec3(10, 10, 10));
  Mesh doubled = clean;  // one face's two triangles stored twice
  doubled.triangles.push_back(clean.triangles[2]);
  doubled.triangles.push_back(clean.triangles[3]);
  Mesh inside_out = clean;
  for (auto& t : inside_out.triangles) std::swap(t[1], t[2]);
  // A second cube touching the first at its top corner (10, 10, 10) only.
  const Mesh touching =
      testing::with_shell(clean, testing::box_mesh(Vec3(3, 3, 3)), Vec3(10, 10, 10));
  // Every face pulled 0.05 mm in from its own edges: cracks of 0.05 mm along all 12 edges.
  Mesh cracked;
  for (const auto& t : clean.triangles) {
    const Vec3 n = (clean.vertices_mm[t[1]] - clean.vertices_mm[t[0]])
                       .cross(clean.vertices_mm[t[2]] - clean.vertices_mm[t[0]])
                       .normalized();
    std::array<int, 3> tri{};
    for (int k = 0; k < 3; ++k) {
      Vec3 v = clean.vertices_mm[t[k]];
      for (int a = 0; a < 3; ++a) {
        if (std::abs(n[a]) > 0.5) continue;  // along the face, not across it
        v[a] = v[a] < 5 ? 0.05 : 9.95;
      }
      tri[k] = static_cast<int>(cracked.vertices_mm.size());
      cracked.vertices_mm.push_back(v);
    }
    cracked.triangles.push_back(tri);
  }
  const Region square = rect_region(0, 0, 10, 10);
  for (const auto& [name, mesh] :
       std::vector<std::pair<std::string, Mesh>>{{"clean", clean},
                                                 {"doubled face", doubled},
                                                 {"inside out", inside_out},
                                                 {"touching vertex", touching},
                                                 {"0.05 mm cracks", cracked}}) {
    ContourStats stats;
    const auto layers = slice_layers(mesh, 1.0, 10, &stats);
    for (std::size_t k = 0; k < layers.size(); ++k) {
      ASSERT_EQ(layers[k].size(), 1u) << name << " layer " << k;
      EXPECT_LT(differ_mm2(layers[k], square), 0.01 * 40) << name << " layer " << k;
      EXPECT_LT(off_boundary_mm(layers[k], {{0, 0, 10, 10}}), 0.05 + 1e-9) << name;
    }
    if (name == "0.05 mm cracks") {
      EXPECT_GT(stats.gaps_closed, 0u);
      EXPECT_NEAR(stats.widest_gap_mm, 0.05 * std::sqrt(2.0), 1e-6) << "corner to corner";
    } else {
      EXPECT_EQ(stats.gaps_closed, 0u) << name;
    }
    // Through prepare_mesh (as `strand slice` does): the same square, defects reported.
    const PreparedMesh p = prepare_mesh(mesh, PrepareOptions{}, "mesh");
    for (const Region& r : slice_layers(p.mesh, 1.0, 10)) {
      EXPECT_LT(differ_mm2(r, square), 0.01 * 40) << name;
    }
    EXPECT_NEAR(signed_volume_mm3(p.mesh), name == "touching vertex" ? 1027.0 : 1000.0,
                name == "0.05 mm cracks" ? 25.0 : 1e-6)
        << name;
  }
}

TEST(MeshSlicer, CavityStaysAHole) {
  // A 20 mm cube with a closed 10 mm cavity (inward-facing shell) in its middle.
  Mesh cavity = testing::box_mesh(Vec3(10, 10, 10));
  for (auto& t : cavity.triangles) std::swap(t[1], t[2]);
  const Mesh part = testing::with_shell(testing::box_mesh(Vec3(20, 20, 20)), cavity, Vec3(5, 5, 5));
  const Region r = slice_layers(part, 1.0, 20)[10];
  ASSERT_EQ(r.size(), 1u);
  ASSERT_EQ(r[0].holes.size(), 1u);
  EXPECT_NEAR(area_mm2(r), 300.0, 1e-6);
}

TEST(MeshSlicer, OpenTubeIsClosedAcrossItsSlot) {
  // A cylinder with a 1 mm slot cut out of its wall (all triangles of one column removed):
  // each layer's contour is closed across the slot.
  Mesh m = testing::tube_mesh(10, 0, 4, 64);
  Mesh open;
  open.vertices_mm = m.vertices_mm;
  for (const auto& t : m.triangles) {
    bool side = true, in_slot = true;
    for (int k = 0; k < 3; ++k) {
      const Vec3& v = m.vertices_mm[t[k]];
      side = side && std::abs(v.head<2>().norm() - 10) < 1e-6;
      in_slot = in_slot && v.x() > 9.5 && std::abs(v.y()) < 1.0;
    }
    if (!(side && in_slot)) open.triangles.push_back(t);
  }
  ASSERT_LT(open.triangles.size(), m.triangles.size());
  ContourStats stats;
  const auto layers = slice_layers(open, 1.0, 4, &stats);
  for (const Region& r : layers) EXPECT_NEAR(area_mm2(r), kPi * 100, 2.0);
  EXPECT_EQ(stats.gaps_closed, 4u);
}

}  // namespace
}  // namespace strand::slicer
