// Slicing by objects (issue 33): the two objects of samples/meshes/two-boxes.3mf in two printheads
// (build order, transforms applied), each layer one strand per head and no crossing between
// them by `strand check`'s own analysis, E per head that of its object's beads; the same
// objects as --part files give the same moves; overlapping objects and bad --part refused.
#include "jobs/slice_objects.h"

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>

#include "postprocess/inspect/check.h"
#include "postprocess/inspect/gcode_parser.h"
#include "slicer/input_error.h"
#include "slicer/mesh_io.h"
#include "tests/support/cli_runner.h"
#include "tests/support/mesh_shapes.h"

namespace strand::jobs {
namespace {

// Two E-driven heads, the second 40 mm right of the first, 2 mm3 of ink per E.
constexpr char kTwoScrews[] = R"({
  "name": "two-screws", "description": "two E-driven heads",
  "kinematics": {"type": "cartesian", "min_mm": [0, 0, 0], "max_mm": [200, 200, 100], "part_center_mm": [100, 100]},
  "firmware": {"flavour": "marlin", "arcs": false},
  "deposition": {"model": "e-volumetric", "mm3_per_e": 1.0, "relative_e": true},
  "tools": [{"name": "soft"},
            {"name": "stiff", "offset_mm": [40, 0, 0],
             "deposition": {"model": "e-volumetric", "mm3_per_e": 2.0, "relative_e": true}}]})";

std::string two_boxes() { return std::string(STRAND_SOURCE_DIR) + "/samples/meshes/two-boxes.3mf"; }

SliceSettings settings(const std::string& dir) {
  std::ofstream(dir + "/two-screws.json") << kTwoScrews;
  SliceSettings s;
  s.machine = dir + "/two-screws.json";
  s.pattern_values = {{"nozzle", 0.6}, {"gap", 1.0}};
  return s;
}

// The G-code's moves and tool changes, without the header's comments (which name the inputs).
std::string moves_only(const std::string& gcode) {
  std::istringstream in(gcode);
  std::string line, out;
  while (std::getline(in, line)) {
    if (!line.starts_with(";")) out += line + "\n";
  }
  return out;
}

// E pushed per head, walking the text (relative E).
std::map<int, double> e_per_tool(const std::string& gcode) {
  std::istringstream in(gcode);
  std::string line;
  int tool = 0;
  std::map<int, double> e;
  while (std::getline(in, line)) {
    if (line.size() > 1 && line[0] == 'T' && std::isdigit(static_cast<unsigned char>(line[1]))) tool = std::stoi(line.substr(1));
    if (!line.starts_with("G1 ")) continue;
    const auto at = line.find(" E");
    if (at != std::string::npos) e[tool] += std::stod(line.substr(at + 2));
  }
  return e;
}

TEST(SliceObjects, ThreeMfBuildItemsKeepApartWithTheirTransforms) {
  const std::vector<slicer::Mesh> objects = slicer::read_mesh_objects(two_boxes());
  ASSERT_EQ(objects.size(), 2u);
  // Build item 0 is resource 2 (the "left box"), item 1 resource 1 turned 90 degrees and moved.
  EXPECT_EQ(slicer::bounds(objects[0]).min_mm, slicer::Vec3(0, 0, 0));
  EXPECT_EQ(slicer::bounds(objects[0]).max_mm, slicer::Vec3(10, 10, 3));
  EXPECT_EQ(slicer::bounds(objects[1]).min_mm, slicer::Vec3(12, 0, 0));
  EXPECT_EQ(slicer::bounds(objects[1]).max_mm, slicer::Vec3(22, 10, 3));
  EXPECT_NEAR(slicer::signed_volume_mm3(objects[1]), 300.0, 1e-9) << "outward after the turn";
  EXPECT_EQ(slicer::merge_meshes(objects).triangles.size(), slicer::read_mesh_file(two_boxes()).triangles.size());
}

TEST(SliceObjects, TwoObjectsInTwoHeadsOneStrandEachNoCrossing) {
  const auto dir = testing::fresh_dir("slice-objects");
  SliceSettings s = settings(dir);
  s.part = two_boxes();
  s.tools = "objects=1,0";
  const SliceResult r = produce_slice(s);
  const std::string& gcode = r.produced.gcode;

  // strand check's own reading: per layer one strand per head, no crossing at all.
  const post::CheckReport check = post::check_gcode(gcode, {});
  ASSERT_EQ(check.layers.size(), 6u);
  EXPECT_TRUE(check.ok()) << post::to_text(check);
  EXPECT_EQ(check.crossing_count(), 0u);
  EXPECT_EQ(check.crossings_between_tools(), 0u);
  for (const auto& layer : check.layers) EXPECT_EQ(layer.strands_by_tool, (std::vector<int>{1, 1})) << layer.layer;

  // The head loaded last prints first in the next layer: one change per layer (T0, the head
  // the machine starts with, first in layer 0).
  EXPECT_EQ(r.produced.report["totals"]["tool_changes"], 6);

  // Read back through the offsets: T1 deposits only over object 0 (x 89..99 once centred at
  // x = 100), T0 only over object 1 (101..111); E per head is its beads' volume.
  const post::ParsedGcode parsed = post::parse_gcode(gcode);
  std::map<int, double> length;
  slicer::Vec3 at = parsed.program.start_mm;
  for (const slicer::Move& m : parsed.program.moves) {
    if (m.kind == slicer::MoveKind::Deposit) {
      length[m.tool] += (m.end_mm - at).head<2>().norm();
      const double x = m.end_mm.x();
      if (m.tool == 1) {
        EXPECT_TRUE(x > 89.0 && x < 99.0) << x;
      }
      if (m.tool == 0) {
        EXPECT_TRUE(x > 101.0 && x < 111.0) << x;
      }
    }
    if (m.kind == slicer::MoveKind::Deposit || m.kind == slicer::MoveKind::Travel) at = m.end_mm;
  }
  const double bead = r.toolpath.derived.at("bead_area_mm2").get<double>();
  const std::map<int, double> e = e_per_tool(gcode);
  ASSERT_GT(length[0], 100.0);
  EXPECT_NEAR(length[0], length[1], 1e-6) << "two equal boxes, one filled pattern each";
  EXPECT_NEAR(e.at(0), length[0] * bead / 1.0, 0.01 * e.at(0));
  EXPECT_NEAR(e.at(1), length[1] * bead / 2.0, 0.01 * e.at(1));

  // The same objects as --part files (written from the 3MF's objects): the same moves.
  const std::vector<slicer::Mesh> objects = slicer::read_mesh_objects(two_boxes());
  testing::write_binary_stl(objects[0], dir + "/left.stl");
  testing::write_binary_stl(objects[1], dir + "/right.stl");
  SliceSettings p = settings(dir);
  p.parts = {part_from_text(dir + "/left.stl:1"), part_from_text(dir + "/right.stl:0")};
  EXPECT_EQ(moves_only(produce_slice(p).produced.gcode), moves_only(gcode));

  // As given: each layer T1 then T0, two changes per layer (the first T1 is a selection).
  s.tool_order = "given";
  EXPECT_EQ(produce_slice(s).produced.report["totals"]["tool_changes"], 11);
}

TEST(SliceObjects, RefusesOverlapsBadPartsAndToolsOffTheMachine) {
  const auto dir = testing::fresh_dir("slice-objects-bad");
  testing::write_binary_stl(testing::box_mesh({10, 10, 3}), dir + "/a.stl");
  slicer::Mesh shifted = testing::box_mesh({10, 10, 3});
  for (auto& v : shifted.vertices_mm) v.x() += 8.0;  // 2 mm into a.stl
  testing::write_binary_stl(shifted, dir + "/b.stl");
  SliceSettings s = settings(dir);
  s.parts = {{dir + "/a.stl", 1}, {dir + "/b.stl", 0}};
  try {
    produce_slice(s);
    FAIL() << "overlapping parts sliced";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("a.stl and " + dir + "/b.stl overlap in layer 0"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos);
  }
  for (const char* bad : {"a.stl", "a.stl:", "a.stl:x", "a.stl:16", "a.stl:-1", ":1"}) {
    try {
      part_from_text(bad);
      ADD_FAILURE() << bad;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("--part = " + std::string(bad) + ": must be FILE:TOOL"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(part_from_text("C:/x/a.stl:3"), (SlicePart{"C:/x/a.stl", 3}));
  SliceSettings wide = settings(dir);
  wide.part = two_boxes();
  wide.tools = "objects=1,0,1";
  EXPECT_THROW(produce_slice(wide), InputError);
  wide.tools = "objects";
  wide.machine = "deltawasp-2040-clay";  // one head: object 1's tool 1 is not on it
  try {
    produce_slice(wide);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("slice.tools = objects: tool 1"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace strand::jobs
