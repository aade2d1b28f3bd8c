#include "slicer/mesh_substrate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "slicer/input_error.h"
#include "slicer/units.h"
#include "tests/support/mesh_shapes.h"

namespace strand::slicer {
namespace {

using testing::box_mesh;
using testing::saddle_mesh;
using testing::sphere_cap_mesh;

const Vec3 kCentre(-20.0, 0.0, 40.0);  // the sample cap's sphere centre; it faces +x

double angle_deg(const Vec3& a, const Vec3& b) {
  return rad_to_deg(std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)));
}

TEST(MeshSubstrate, ASphereCapFacingSidewaysMapsOntoItsOffsetSpheres) {
  const MeshSubstrate s(sphere_cap_mesh(kCentre, Vec3::UnitX(), 40.0, 50.0, 24, 96), "cap");
  EXPECT_TRUE(s.facing().isApprox(Vec3::UnitX(), 1e-9));
  EXPECT_EQ(s.kind(), "mesh");
  EXPECT_EQ(s.uv_source(), "least-squares conformal (CGAL)");
  EXPECT_LT(s.distortion().stretch_max, 1.1);
  // The map's v runs along the flange axis (workpiece z), as a cylinder's.
  const SurfaceFrame centre = s.frame_at(Vec2::Zero(), 0.0);
  EXPECT_LT(angle_deg(centre.d_dv, Vec3::UnitZ()), 10.0);
  for (const Vec2& uv : {Vec2(0, 0), Vec2(12.5, -3.0), Vec2(-20.0, 18.0), Vec2(7.0, 25.0)}) {
    for (const double offset : {0.0, 0.96, 2.88}) {
      const SurfaceFrame f = s.frame_at(uv, offset);
      // On the sphere of radius 40 + offset within the facets' sagitta, normals radial.
      EXPECT_NEAR((f.point_mm - kCentre).norm(), 40.0 + offset, 0.05) << uv.transpose();
      EXPECT_LT(angle_deg(f.normal, f.point_mm - kCentre), 1.0) << uv.transpose();
      // Mapped back: the same offset, (u, v) and normal; the point lies on that offset surface.
      const auto back = s.locate(f.point_mm);
      EXPECT_NEAR(back.offset_mm, offset, 1e-6);
      EXPECT_LT(back.residual_mm, 1e-6);
      EXPECT_LT((back.uv_mm - uv).norm(), 1e-6);
      EXPECT_LT(angle_deg(back.normal, f.normal), 1e-6);
    }
  }
}

TEST(MeshSubstrate, ASaddleKeepsItsOutsideAndMapsBack) {
  const MeshSubstrate s(saddle_mesh(Vec3(20.0, 0.0, 40.0), Vec3::UnitX(), 50.0, 60.0, 40),
                        "saddle");
  EXPECT_GT(s.facing().x(), 0.99);
  for (const Vec2& uv : {Vec2(0, 0), Vec2(15.0, 15.0), Vec2(-18.0, 10.0)}) {
    const SurfaceFrame f = s.frame_at(uv, 1.5);
    const auto back = s.locate(f.point_mm);
    EXPECT_NEAR(back.offset_mm, 1.5, 1e-6);
    EXPECT_LT(back.residual_mm, 1e-6);
    EXPECT_LT((back.uv_mm - uv).norm(), 1e-6);
    EXPECT_GT(f.normal.x(), 0.7);  // the outside, towards the nozzle
  }
  // A point off the offset surfaces (beside the normal) says how far.
  const SurfaceFrame f = s.frame_at(Vec2(5.0, 5.0), 1.0);
  const auto off = s.locate(f.point_mm + 0.3 * f.d_du.normalized());
  EXPECT_GT(std::hypot(off.residual_mm, off.offset_mm - 1.0) + (off.uv_mm - Vec2(5, 5)).norm(),
            0.2);
}

TEST(MeshSubstrate, AClosedMeshOrAPointOffTheMapIsRefusedNamingIt) {
  try {
    MeshSubstrate s(box_mesh(Vec3(10, 10, 10)), "box.stl");
    ADD_FAILURE() << "a closed box has no outside facing one way";
  } catch (const InputError& e) {
    EXPECT_EQ(
        std::string(e.what()).rfind("substrate.mesh = box.stl: its outside faces every way", 0), 0u)
        << e.what();
  }
  const MeshSubstrate s(sphere_cap_mesh(kCentre, Vec3::UnitX(), 40.0, 50.0, 12, 48), "cap.stl");
  EXPECT_FALSE(s.in_domain(Vec2(60.0, 0.0)));
  try {
    s.frame_at(Vec2(60.0, 0.0), 1.0);
    ADD_FAILURE() << "outside the map";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("substrate.mesh = cap.stl: the pattern leaves the mesh at "
                                         "pattern point (u, v) = (60.000, 0.000) mm"),
              std::string::npos)
        << e.what();
  }
}

TEST(MeshSubstrate, TheNozzleConeSeesTheMeshInTheWorkpieceFrame) {
  const MeshSubstrate s(sphere_cap_mesh(kCentre, Vec3::UnitX(), 40.0, 50.0, 16, 64), "cap");
  const SurfaceFrame top = s.frame_at(Vec2::Zero(), 0.96);
  // Above a convex cap, along its normal: clear. Pointing back into it: the cap is hit.
  EXPECT_FALSE(s.cone_hit(NozzleCone{}, top.point_mm, top.normal).has_value());
  EXPECT_TRUE(s.cone_hit(NozzleCone{}, top.point_mm, -top.normal).has_value());
}

TEST(MeshSubstrateRecord, RoundTripAndPathsBesideTheCsv) {
  MeshSubstrateRecord r{"../meshes/cap.stl",
                        "0123456789abcdef",
                        "kuka-iiwa14-wasp-cylinder",
                        {0.96, 1.92},
                        NozzleCone{25.0, 30.0, 0.8}};
  EXPECT_EQ(mesh_record_from_json(to_json(r), "x"), r);
  EXPECT_EQ(mesh_record_path("out/part.csv"), "out/part.substrate.json");
  EXPECT_EQ(mesh_path_from_record(r, "out/part.csv"), "meshes/cap.stl");
  EXPECT_THROW(mesh_record_from_json({{"substrate", "mesh"}}, "x"), InputError);
  EXPECT_EQ(content_fingerprint(""), "cbf29ce484222325");  // FNV-1a 64 offset basis
  EXPECT_NE(content_fingerprint("a"), content_fingerprint("b"));
}

}  // namespace
}  // namespace strand::slicer
