// A mesh made coarse for drawing keeps its shape to about a cell and stays under the count.
#include "slicer/mesh_decimate.h"

#include <gtest/gtest.h>

#include "tests/support/mesh_shapes.h"

namespace strand::slicer {
namespace {

TEST(MeshDecimate, ATorusOfFortyThousandTrianglesDrawsInTwoThousandKeepingItsShape) {
  const Mesh torus = testing::torus_mesh(20, 6, 200, 100);  // 40,000 triangles
  ASSERT_EQ(torus.triangles.size(), 40000u);
  const Decimated d = decimate_for_drawing(torus, 2000);
  EXPECT_LE(d.mesh.triangles.size(), 2000u);
  EXPECT_GE(d.mesh.triangles.size(), 1000u) << "the finest grid under the count, not a coarser one";
  EXPECT_GT(d.cell_mm, 0.5);
  EXPECT_LT(d.cell_mm, 3.0);
  // Every vertex is a mean of vertices of one cell: within a cell's diagonal of the surface
  // (the tube's circle), and the bounds match to a cell.
  for (const Vec3& v : d.mesh.vertices_mm) {
    const double ring = std::hypot(v.x(), v.y()) - 20;
    const double off = std::abs(std::hypot(ring, v.z() - 6) - 6);
    EXPECT_LE(off, d.cell_mm * 1.7321) << v.transpose();
  }
  const Box3 a = bounds(torus), b = bounds(d.mesh);
  EXPECT_LE((a.min_mm - b.min_mm).cwiseAbs().maxCoeff(), d.cell_mm);
  EXPECT_LE((a.max_mm - b.max_mm).cwiseAbs().maxCoeff(), d.cell_mm);
  for (const auto& t : d.mesh.triangles) {
    EXPECT_TRUE(t[0] != t[1] && t[1] != t[2] && t[0] != t[2]);
    for (int k : t) EXPECT_LT(static_cast<std::size_t>(k), d.mesh.vertices_mm.size());
  }
  EXPECT_EQ(decimate_for_drawing(torus, 2000).mesh, d.mesh) << "deterministic";
}

TEST(MeshDecimate, ASoupOfOverlappingShellsAndASmallMeshPassAsTheyAre) {
  // Two overlapping boxes as one soup (not a manifold surface): clustering takes it.
  const Mesh soup = testing::with_shell(testing::box_mesh({10, 10, 10}), testing::box_mesh({10, 10, 10}), {5, 5, 5});
  const Decimated d = decimate_for_drawing(soup, 12);
  EXPECT_LE(d.mesh.triangles.size(), 12u);
  EXPECT_GT(d.cell_mm, 0.0);
  const Decimated same = decimate_for_drawing(soup, 24);
  EXPECT_EQ(same.mesh.triangles, soup.triangles);
  EXPECT_EQ(same.cell_mm, 0.0);
}

}  // namespace
}  // namespace strand::slicer
