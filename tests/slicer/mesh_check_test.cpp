// Mesh validation says what is wrong and where; --repair fixes holes and orientation.
#include "slicer/mesh_check.h"

#include <gtest/gtest.h>

#include "slicer/input_error.h"
#include "tests/support/mesh_shapes.h"

namespace strand::slicer {
namespace {

using testing::box_mesh;

std::string prepare_error(const Mesh& m, bool repair) {
  try {
    prepare_mesh(m, repair, "mesh = part.stl");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(MeshCheck, ClosedShapesPass) {
  for (const Mesh& m : {box_mesh(Vec3(1, 2, 3)), testing::tube_mesh(5, 2, 3, 32),
                        testing::torus_mesh(10, 3, 32, 16)}) {
    const MeshCheck c = check_mesh(m);
    EXPECT_TRUE(c.ok()) << c.problem;
    EXPECT_FALSE(c.inside_out);
  }
}

TEST(MeshCheck, OpenMeshNamesABorderEdgeWithCoordinates) {
  Mesh m = box_mesh(Vec3(10, 10, 10));
  m.triangles.pop_back();
  const MeshCheck c = check_mesh(m);
  EXPECT_EQ(c.border_edges, 3u);
  EXPECT_NE(c.problem.find("open mesh"), std::string::npos);
  EXPECT_NE(c.problem.find("(10.000, "), std::string::npos) << c.problem;
  const std::string e = prepare_error(m, false);
  EXPECT_NE(e.find("mesh = part.stl: open mesh"), std::string::npos) << e;
  EXPECT_NE(e.find("--repair"), std::string::npos);
}

TEST(MeshCheck, FlippedTriangleIsInconsistentOrientation) {
  Mesh m = box_mesh(Vec3(1, 1, 1));
  std::swap(m.triangles[4][1], m.triangles[4][2]);
  const MeshCheck c = check_mesh(m);
  EXPECT_GT(c.misoriented_edges, 0u);
  EXPECT_NE(c.problem.find("inconsistently oriented"), std::string::npos);
}

TEST(MeshCheck, ThreeTrianglesOnOneEdgeAreNonManifold) {
  Mesh m = box_mesh(Vec3(1, 1, 1));
  const int v = static_cast<int>(m.vertices_mm.size());
  m.vertices_mm.push_back(Vec3(0.5, 0.5, 3));
  m.triangles.push_back({m.triangles[2][0], m.triangles[2][1], v});
  EXPECT_GT(check_mesh(m).non_manifold_edges, 0u);
}

// Two cubes of side `side_mm`, the second moved by `offset`, as one mesh (each its own vertices).
Mesh two_cubes(double side_mm, const Vec3& offset) {
  Mesh a = box_mesh(Vec3(side_mm, side_mm, side_mm));
  const Mesh b = a;
  const int base = static_cast<int>(a.vertices_mm.size());
  for (const Vec3& v : b.vertices_mm) a.vertices_mm.push_back(v + offset);
  for (const auto& t : b.triangles) a.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  return a;
}

TEST(MeshCheck, OverlappingBoxesSelfIntersect) {
  const Mesh a = two_cubes(2, Vec3(1, 1, 1));
  const MeshCheck c = check_mesh(a);
  EXPECT_GT(c.self_intersections, 0u);
  EXPECT_NE(c.problem.find("self-intersecting"), std::string::npos);
  EXPECT_NE(prepare_error(a, true).find("--repair does not cut"), std::string::npos);
}

TEST(MeshCheck, BoxesMeetingAtACornerTouchAtASingleVertex) {
  // Every edge is used once each way, but the shared corner has two fans of triangles.
  const MeshCheck c = check_mesh(two_cubes(1, Vec3(1, 1, 1)));
  EXPECT_TRUE(c.touching_vertex);
  EXPECT_EQ(c.non_manifold_edges + c.border_edges + c.misoriented_edges, 0u);
  EXPECT_NE(c.problem.find("single vertex"), std::string::npos) << c.problem;
  // Apart, each box is sound.
  const MeshCheck apart = check_mesh(two_cubes(1, Vec3(1.5, 1, 1)));
  EXPECT_TRUE(apart.ok()) << apart.problem;
}

TEST(MeshCheck, InsideOutIsReversedAndReported) {
  Mesh m = box_mesh(Vec3(1, 2, 3));
  for (auto& t : m.triangles) std::swap(t[1], t[2]);
  EXPECT_TRUE(check_mesh(m).inside_out);
  const PreparedMesh p = prepare_mesh(m, false, "mesh");
  EXPECT_NEAR(signed_volume_mm3(p.mesh), 6.0, 1e-9);
  ASSERT_EQ(p.changes.size(), 1u);
  EXPECT_NE(p.changes[0].find("reversed"), std::string::npos);
}

TEST(MeshCheck, RepairFillsAHoleAndReportsIt) {
  Mesh m = testing::tube_mesh(5, 0, 4, 24);
  // Two neighbouring triangles of the top cap's fan (the fan alternates bottom, top).
  m.triangles.erase(m.triangles.end() - 3);
  m.triangles.pop_back();
  const PreparedMesh p = prepare_mesh(m, true, "mesh");
  EXPECT_TRUE(check_mesh(p.mesh).ok());
  bool filled = false;
  for (const auto& c : p.changes)
    filled = filled || c.find("filled holes: 1 (2 triangles)") != std::string::npos;
  EXPECT_TRUE(filled) << ::testing::PrintToString(p.changes);
  EXPECT_NEAR(signed_volume_mm3(p.mesh), signed_volume_mm3(testing::tube_mesh(5, 0, 4, 24)), 1e-6);
}

TEST(MeshCheck, RepairStitchesDuplicatedSeams) {
  // The same box with one face's corners duplicated (as some exporters write seams).
  Mesh m = box_mesh(Vec3(3, 3, 3));
  const int base = static_cast<int>(m.vertices_mm.size());
  for (int k = 0; k < 3; ++k)
    m.vertices_mm.push_back(m.vertices_mm[m.triangles[0][k]] + Vec3(1e-4, 0, 0));
  m.triangles[0] = {base, base + 1, base + 2};
  EXPECT_FALSE(check_mesh(m).ok());
  EXPECT_NE(prepare_error(m, false).find("open mesh"), std::string::npos);
}

TEST(MeshCheck, FlatAndZeroVolumeMeshesAreRejected) {
  Mesh flat;
  flat.vertices_mm = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  flat.triangles = {{0, 1, 2}, {0, 2, 1}};
  EXPECT_NE(prepare_error(flat, false).find("flat mesh"), std::string::npos);
}

Mesh two_boxes(const Vec3& offset) {
  Mesh a = box_mesh(Vec3(1, 1, 1));
  const Mesh b = box_mesh(Vec3(1, 1, 1));
  const int base = static_cast<int>(a.vertices_mm.size());
  for (const Vec3& v : b.vertices_mm) a.vertices_mm.push_back(v + offset);
  for (const auto& t : b.triangles) a.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  return a;
}

TEST(MeshCheck, RepairNeverAddsNonManifoldEdges) {
  // Two boxes touching along a vertical edge, each with its own vertices (as an indexed
  // file stores them): welding the duplicate positions would share that edge by 4 triangles.
  const Mesh m = two_boxes(Vec3(1, 1, 0));
  ASSERT_EQ(check_edges_as_indexed(m).non_manifold_edges, 0u);
  ASSERT_GT(check_mesh(m).non_manifold_edges, 0u) << "welded, the edge is non-manifold";
  const PreparedMesh p = prepare_mesh(m, PrepareOptions{true, false}, "mesh");
  const MeshCheck after = check_edges_as_indexed(p.mesh);
  EXPECT_EQ(after.non_manifold_edges, 0u) << ::testing::PrintToString(p.changes);
  EXPECT_EQ(after.border_edges, 0u);
  EXPECT_NEAR(signed_volume_mm3(p.mesh), 2.0, 1e-9);
}

TEST(MeshCheck, DefectsAreReportedNotFatalUnlessStrict) {
  const Mesh overlapping = two_boxes(Vec3(0.5, 0.5, 0.5));
  const PreparedMesh p = prepare_mesh(overlapping, PrepareOptions{}, "mesh = part.stl");
  ASSERT_EQ(p.defects.size(), 1u) << ::testing::PrintToString(p.defects);
  // Slicing looks for the first crossing only; the pairs are counted by `strand mesh`.
  EXPECT_EQ(p.defects[0],
            "mesh: self-intersecting triangles resolved by contour union (strand mesh "
            "counts the pairs)");
  EXPECT_TRUE(p.before.self_intersecting);
  EXPECT_EQ(p.before.self_intersections, 0u) << "not counted";
  const MeshCheck counted = check_mesh(overlapping);
  EXPECT_TRUE(counted.self_intersecting);
  EXPECT_GT(counted.self_intersections, 0u);
  const MeshCheck first = check_mesh(overlapping, Crossings::First);
  EXPECT_TRUE(first.self_intersecting);
  EXPECT_EQ(first.self_intersections, 0u);
  EXPECT_FALSE(check_mesh(box_mesh(Vec3(1, 2, 3)), Crossings::First).self_intersecting);
  try {
    prepare_mesh(overlapping, PrepareOptions{false, true}, "mesh = part.stl");
    ADD_FAILURE() << "strict refuses";
  } catch (const InputError& e) {
    // A refusal counts the pairs and names where.
    EXPECT_EQ(std::string(e.what()).rfind("mesh = part.stl: self-intersecting: " +
                                              std::to_string(counted.self_intersections) +
                                              " pair(s) of triangles cut each other, e.g. near (",
                                          0),
              0u)
        << e.what();
  }
}

TEST(MeshCheck, DoubledAndOppositeTrianglesAreLeftOut) {
  Mesh m = box_mesh(Vec3(2, 2, 2));
  m.triangles.push_back(m.triangles[0]);  // a copy
  const auto t = m.triangles[1];
  m.triangles.push_back({t[0], t[2], t[1]});  // and a copy facing the other way
  const PreparedMesh p = prepare_mesh(m, PrepareOptions{}, "mesh");
  EXPECT_EQ(p.mesh.triangles.size(), 11u) << "the copy goes; the opposite pair goes both";
  bool said = false;
  for (const auto& d : p.defects)
    said = said || d.find("3 doubled triangles left out") != std::string::npos;
  EXPECT_TRUE(said) << ::testing::PrintToString(p.defects);
}

}  // namespace
}  // namespace strand::slicer
