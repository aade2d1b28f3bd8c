// A mesh patch as a Surface: points on the mesh, unit normals, tangents that are the map's
// derivatives, file UVs kept, a conformal map computed when there are none.
#include "slicer/mesh_surface.h"

#include <gtest/gtest.h>

#include <cmath>

#include "slicer/input_error.h"
#include "tests/support/mesh_shapes.h"

namespace strand::slicer {
namespace {

constexpr double kW = 60, kD = 40, kSag = 3;
// The plate's height field and its gradient (tests/support/mesh_shapes.cpp).
double plate_z(double x, double y) {
  return kSag * (1.0 - 2.0 * (x * x + y * y) / (kW * kW + kD * kD));
}
Vec3 plate_normal(double x, double y) {
  const double k = -4.0 * kSag / (kW * kW + kD * kD);
  return Vec3(-k * x, -k * y, 1.0).normalized();
}

TEST(MeshSurface, FileUvsPutPointsOnTheMeshWithUnitNormalsAndTangents) {
  const MeshSurface s(testing::plate_mesh(kW, kD, kSag, 60, 40), "plate.obj");
  EXPECT_EQ(s.uv_source(), "file UVs");
  for (double u : {-25.0, -3.3, 0.0, 12.5, 28.0}) {
    for (double v : {-18.0, 0.0, 7.7}) {
      ASSERT_TRUE(s.in_domain(Vec2(u, v)));
      const SurfaceFrame f = s.frame_at(Vec2(u, v), 0.0);
      EXPECT_NEAR(f.point_mm.z(), plate_z(f.point_mm.x(), f.point_mm.y()), 0.01);
      EXPECT_NEAR(f.normal.norm(), 1.0, 1e-12);
      EXPECT_GT(f.normal.dot(plate_normal(f.point_mm.x(), f.point_mm.y())), std::cos(0.01));
      EXPECT_NEAR(f.d_du.dot(f.normal), 0.0, 0.01) << "tangent";
      EXPECT_NEAR(f.d_dv.dot(f.normal), 0.0, 0.01) << "tangent";
      const SurfaceFrame up = s.frame_at(Vec2(u, v), 2.0);
      EXPECT_TRUE((up.point_mm - f.point_mm).isApprox(2.0 * f.normal, 1e-12));
    }
  }
  EXPECT_FALSE(s.in_domain(Vec2(40, 0)));
  EXPECT_EQ(s.describe().at("kind"), "mesh");
}

TEST(MeshSurface, ConformalMapWithoutUvsIsNearlyIsometricOnAGentlePlate) {
  Mesh m = testing::plate_mesh(kW, kD, kSag, 30, 20);
  m.uv.clear();
  const MeshSurface s(m, "plate.stl");
  EXPECT_EQ(s.uv_source(), "least-squares conformal (CGAL)");
  EXPECT_GT(s.distortion().area_ratio_min, 0.95);
  EXPECT_LT(s.distortion().area_ratio_max, 1.05);
  EXPECT_LT(s.distortion().stretch_max, 1.05);
  const UvBox d = s.domain();
  EXPECT_NEAR(d.max_mm.x() - d.min_mm.x(), kW, 1.5) << "lined up with the top view, mm";
  EXPECT_NEAR(d.max_mm.y() - d.min_mm.y(), kD, 1.5);
  const SurfaceFrame f = s.frame_at(Vec2(20, 0), 0.0);
  EXPECT_NEAR(f.point_mm.x(), 20, 1.0) << "+u runs along +x";
  EXPECT_NEAR(f.point_mm.z(), plate_z(f.point_mm.x(), f.point_mm.y()), 0.01);
  EXPECT_NEAR(f.d_du.norm(), 1.0, 0.05) << "lengths roughly kept";
}

TEST(MeshSurface, ClosedMeshWithoutUvsIsNotAPatch) {
  try {
    const MeshSurface s(testing::box_mesh(Vec3(1, 1, 1)), "box.stl");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("onto = box.stl: not a disk-like patch"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace strand::slicer
