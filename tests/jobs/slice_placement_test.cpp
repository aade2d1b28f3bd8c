// A slice's recorded placement (jobs/slice_placement.h): the report's matrix takes the kept
// mesh file onto the part as sliced, in machine coordinates (turned, scaled, up axis, a 3MF's
// objects); the mesh read back is bounded, read by name only inside a folder, and a malformed
// record is refused.
#include "jobs/slice_placement.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "slicer/input_error.h"
#include "slicer/mesh_io.h"
#include "tests/support/cli_runner.h"
#include "tests/support/mesh_shapes.h"

namespace strand::jobs {
namespace {

using nlohmann::json;

slicer::Box3 box_of(const slicer::TriangleMesh& m) { return slicer::bounds(slicer::Mesh{m.vertices_mm, m.triangles, {}}); }

// A 20 x 10 x 4 box written as STL, sliced standing up (+Y up), turned and scaled to fit.
std::string box_stl(const std::string& dir) {
  const std::string path = dir + "/box.stl";
  std::ofstream(path, std::ios::binary) << slicer::binary_stl_bytes(testing::box_mesh(slicer::Vec3(20, 10, 4)));
  return path;
}

SliceSettings turned(const std::string& part) {
  SliceSettings s;
  s.part = part;
  s.machine = "marlin-xyz-200";  // parts centred at (100, 100)
  s.up = "y";
  s.rotate = "0,0,30";
  s.scale_to_fit = "30x30x30";
  s.pattern_values = {{"nozzle", 0.84}, {"gap", 1.6}};
  return s;
}

void expect_same_box(const slicer::Box3& a, const slicer::Box3& b) {
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(a.min_mm[k], b.min_mm[k], 1e-6) << k;
    EXPECT_NEAR(a.max_mm[k], b.max_mm[k], 1e-6) << k;
  }
}

TEST(SlicePlacement, TheMatrixTakesTheFileOntoTheSlicedPartOnTheMachine) {
  const std::string dir = testing::fresh_dir("placement");
  const SliceResult r = produce_slice(turned(box_stl(dir)));
  const json& p = r.produced.report.at("mesh_placement");
  EXPECT_EQ(p.at("role"), "part");
  EXPECT_EQ(p.at("files"), json::array({dir + "/box.stl"}));
  EXPECT_EQ(p.at("file_to_machine").at(3), json::array({0, 0, 0, 1}));
  const PlacedMesh placed = placed_mesh_from(p, "");
  EXPECT_EQ(placed.triangles, 12u);
  EXPECT_TRUE(placed.note.empty());
  slicer::Box3 sliced = slicer::bounds(r.part.mesh);
  sliced.min_mm += slicer::Vec3(100, 100, 0);
  sliced.max_mm += slicer::Vec3(100, 100, 0);
  expect_same_box(box_of(placed.mesh), sliced);
  EXPECT_NEAR(box_of(placed.mesh).min_mm.z(), 0.0, 1e-9) << "on the bed";
  // Up y stands the 10 mm side up; turned 30 degrees, the footprint's x (20 cos 30 + 4 sin 30)
  // is what fits 30 mm.
  const double scale = 30.0 / (20.0 * std::cos(M_PI / 6) + 4.0 * std::sin(M_PI / 6));
  EXPECT_NEAR(box_of(placed.mesh).size_mm().z(), 10.0 * scale, 1e-6);
  EXPECT_NEAR(box_of(placed.mesh).size_mm().x(), 30.0, 1e-6);
}

TEST(SlicePlacement, ObjectsOfA3mfArePlacedTogether) {
  SliceSettings s;
  s.part = std::string(STRAND_SOURCE_DIR) + "/samples/meshes/two-boxes.3mf";
  s.tools = "objects";
  s.machine = "two-head-pneumatic";
  s.pattern_values = {{"nozzle", 0.6}, {"gap", 1.0}};
  const SliceResult r = produce_slice(s);
  const PlacedMesh placed = placed_mesh_from(r.produced.report.at("mesh_placement"), "");
  const slicer::Vec2 c = machines::load_profile(s.machine).volume.part_center_mm;
  slicer::Box3 sliced = slicer::bounds(r.part.mesh);
  sliced.min_mm += slicer::Vec3(c.x(), c.y(), 0);
  sliced.max_mm += slicer::Vec3(c.x(), c.y(), 0);
  expect_same_box(box_of(placed.mesh), sliced);
}

TEST(SlicePlacement, ALargeMeshIsDrawnSimplifiedWithANote) {
  const std::string dir = testing::fresh_dir("placement-large");
  const json p = produce_slice(turned(box_stl(dir))).produced.report.at("mesh_placement");
  const PlacedMesh placed = placed_mesh_from(p, "", 11);
  EXPECT_LE(placed.mesh.triangles.size(), 11u);
  EXPECT_EQ(placed.triangles, 12u) << "the file's count";
  EXPECT_EQ(placed.note.rfind("the part mesh (12 triangles) is drawn simplified to " +
                                  std::to_string(placed.mesh.triangles.size()) + " (",
                              0),
            0u)
      << placed.note;
  EXPECT_NE(placed.note.find(" mm cells)"), std::string::npos) << placed.note;
}

TEST(SlicePlacement, InAFolderFilesAreReadByNameOnly) {
  const std::string dir = testing::fresh_dir("placement-folder");
  box_stl(dir);
  const json identity = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};
  const json p = {{"role", "part"}, {"files", {"../../elsewhere/box.stl"}}, {"file_to_machine", identity}};
  EXPECT_EQ(placed_mesh_from(p, dir).triangles, 12u) << "the folder's box.stl, not a path outside it";
  const json missing = {{"role", "part"}, {"files", {"../box2.stl"}}, {"file_to_machine", identity}};
  EXPECT_THROW(placed_mesh_from(missing, dir), InputError);
  const json bad = {{"role", "part"}, {"files", {"box.stl"}}, {"file_to_machine", {{1, 0, 0}}}};
  EXPECT_THROW(placed_mesh_from(bad, dir), InputError);
  EXPECT_THROW(placed_mesh_from({{"file_to_machine", identity}}, dir), InputError);
}

}  // namespace
}  // namespace strand::jobs
