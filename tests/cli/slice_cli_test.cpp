// `strand slice` from the outside: every pattern on a part with a hole passes
// `strand check --machine`; bad meshes and flags exit 2 with one line and no file.
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <set>
#include <sstream>
#include <nlohmann/json.hpp>

#include "slicer/file_io.h"
#include "postprocess/inspect/gcode_parser.h"
#include "tests/support/cli_runner.h"
#include "tests/support/gcode_view.h"
#include "tests/support/mesh_shapes.h"

namespace strand::testing {
namespace {

const std::string kMachine = " --machine deltawasp-2040-clay";

// The bone plug of samples/meshes/: a bored cylinder.
std::string plug_dir() {
  const auto dir = fresh_dir("slice");
  write_binary_stl(tube_mesh(10.0, 3.0, 6.0, 96), dir + "/plug.stl");
  return dir;
}

// A Benchy-like part of overlapping shells: a hull box, a cabin box sunk into it and a
// chimney cylinder through the cabin roof, each a closed surface, none cut by the others.
slicer::Mesh boat_mesh() {
  using slicer::Vec3;
  slicer::Mesh m = box_mesh(Vec3(30, 14, 6));
  m = with_shell(m, box_mesh(Vec3(12, 10, 8)), Vec3(4, 2, 3));
  m = with_shell(m, tube_mesh(2.0, 0.0, 8.0, 48), Vec3(10, 7, 6));
  return m;
}

struct PatternCase {
  const char* name;
  const char* flags;
  int max_strands;  // pattern strands per layer on the bone plug (one region, one hole)
};

class SlicePatterns : public ::testing::TestWithParam<PatternCase> {};

TEST_P(SlicePatterns, EveryLayerPassesStrandCheck) {
  const auto dir = plug_dir();
  const auto r = run_strand(
      std::string("slice plug.stl ") + GetParam().flags + kMachine + " -o s.gcode --report s.json",
      dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("strand(s) per layer"), std::string::npos) << r.out;
  const auto check = run_strand("check s.gcode" + kMachine, dir);
  EXPECT_EQ(check.exit_code, 0) << check.out;
  const auto report = nlohmann::json::parse(slurp(dir + "/s.json"));
  for (const auto& n : report.at("derived").at("pattern_strands_per_layer")) {
    EXPECT_LE(n.get<int>(), GetParam().max_strands);
  }
  EXPECT_GT(report.at("derived").at("porosity").get<double>(), 0.0);
  EXPECT_LT(report.at("derived").at("porosity").get<double>(), 1.0);
}

INSTANTIATE_TEST_SUITE_P(
    Patterns, SlicePatterns,
    ::testing::Values(
        PatternCase{"scaffold", "--pattern scaffold --nozzle 0.6 --gap 1", 2},
        PatternCase{"scaffold_perimeters", "--pattern scaffold --nozzle 0.6 --gap 1 --perimeters 2",
                    2},
        PatternCase{"scaffold_angles",
                    "--pattern scaffold --nozzle 0.6 --pitch 2 --angles 0,60,120", 3},
        PatternCase{"tetrachiral", "--pattern tetrachiral --nozzle 0.4 --cell 5 --node-core 1", 4},
        PatternCase{"hexachiral", "--pattern hexachiral --nozzle 0.4 --cell 5.3 --node-core 1", 3},
        PatternCase{"missing_rib", "--pattern missing-rib --nozzle 0.4 --rib 3 --angle 20", 2},
        PatternCase{"reentrant", "--pattern reentrant --nozzle 0.4 --cell-width 4 --cell-height 4",
                    4}),
    [](const auto& info) { return std::string(info.param.name); });

TEST(SliceCli, SameInputGivesIdenticalBytes) {
  const auto dir = plug_dir();
  for (const char* out : {"a.gcode", "b.gcode"}) {
    ASSERT_EQ(
        run_strand(std::string("slice plug.stl --nozzle 0.6 --gap 1 -o ") + out, dir).exit_code, 0);
  }
  EXPECT_EQ(slurp(dir + "/a.gcode"), slurp(dir + "/b.gcode"));
}

TEST(SliceCli, PreviewDrawsThePlacedMeshUnderThePath) {
  const auto dir = plug_dir();
  const auto r = run_strand(
      "slice plug.stl --nozzle 0.6 --gap 1 --machine marlin-xyz-200 -o p.gcode --preview p.glb "
      "--preview p.html",
      dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string glb = slurp(dir + "/p.glb");
  tinygltf::Model m;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromMemory(&m, &err, &warn,
                                          reinterpret_cast<const unsigned char*>(glb.data()),
                                          static_cast<unsigned int>(glb.size())))
      << err;
  const auto substrate = std::find_if(m.nodes.begin(), m.nodes.end(),
                                      [](const auto& n) { return n.name == "substrate"; });
  ASSERT_NE(substrate, m.nodes.end());
  const auto& prim = m.meshes.at(static_cast<std::size_t>(substrate->mesh)).primitives.at(0);
  const auto& pos = m.accessors.at(static_cast<std::size_t>(prim.attributes.at("POSITION")));
  // The tube (radius 10 mm) moved with the part to the machine's part centre (100, 100).
  EXPECT_NEAR(pos.minValues.at(0), 90.0, 0.05);
  EXPECT_NEAR(pos.maxValues.at(0), 110.0, 0.05);
  EXPECT_NE(slurp(dir + "/p.html").find("\"substrate\":{"), std::string::npos);
  expect_input_error(
      run_strand("slice plug.stl --nozzle 0.6 --gap 1 -o q.gcode --preview q.bmp", dir),
      "slice.preview = q.bmp: extension must be");
  EXPECT_FALSE(exists(dir + "/q.gcode"));
}

TEST(SliceCli, RepairMakesAHoledMeshSlice) {
  const auto dir = fresh_dir("slice-repair");
  slicer::Mesh m = tube_mesh(8.0, 0.0, 4.0, 48);
  m.triangles.pop_back();
  write_binary_stl(m, dir + "/holed.stl");
  const auto bad = run_strand("slice holed.stl --nozzle 0.6 --gap 1 --strict -o h.gcode", dir);
  expect_input_error(bad, "open mesh");
  EXPECT_NE(bad.err.find("--repair"), std::string::npos);
  EXPECT_FALSE(exists(dir + "/h.gcode"));
  const auto ok = run_strand("slice holed.stl --nozzle 0.6 --gap 1 --repair -o h.gcode", dir);
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_NE(ok.out.find("repaired       filled holes: 1"), std::string::npos) << ok.out;
  EXPECT_EQ(run_strand("check h.gcode" + kMachine, dir).exit_code, 0);
}

TEST(SliceCli, OntoACurvedPlateFollowsItAndPassesCheck) {
  const auto dir = fresh_dir("slice-onto");
  write_obj(plate_mesh(60, 40, 3, 30, 20), dir + "/plate.obj");
  const auto r = run_strand(
      "slice --onto plate.obj --pattern scaffold --nozzle 0.6 --gap 1 --size 40x24 --layers 2"
      " --machine marlin-xyz-200 -o p.gcode --report p.json",
      dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("substrate      plate.obj: file UVs, 3D/uv area ratio 0.99"),
            std::string::npos)
      << r.out;
  EXPECT_EQ(run_strand("check p.gcode --machine marlin-xyz-200", dir).exit_code, 0);
  const auto report = nlohmann::json::parse(slurp(dir + "/p.json"));
  EXPECT_EQ(report.at("derived").at("substrate").at("kind"), "mesh");
  // The plate's crown drops 0.65 mm from its centre to the pattern's corners (20.3, 12.3):
  // deposits rise and fall with it; flat layers would differ by the 0.528 mm layer only.
  double lo = 1e9, hi = -1e9;
  for (const std::string& line : {slurp(dir + "/p.gcode")}) {
    std::size_t at = 0;
    while ((at = line.find("G1 X", at)) != std::string::npos) {
      const auto z = line.find(" Z", at), eol = line.find('\n', at);
      if (z < eol) {
        const double v = std::stod(line.substr(z + 2));
        lo = std::min(lo, v), hi = std::max(hi, v);
      }
      at = eol;
    }
  }
  EXPECT_GT(hi - lo, 0.528 + 0.3) << "deposits follow the crown";
  EXPECT_LT(hi - lo, 0.528 + 0.7);
  const auto too_big = run_strand(
      "slice --onto plate.obj --pattern scaffold --nozzle 0.6 --gap 1 --size 80x60 "
      "--layers 1 --machine marlin-xyz-200 -o q.gcode",
      dir);
  expect_input_error(too_big, "leaves the substrate");
  EXPECT_FALSE(exists(dir + "/q.gcode"));
}

TEST(SliceCli, OverlappingShellsSliceWithTheirDefectsSaid) {
  const auto dir = fresh_dir("slice-boat");
  write_binary_stl(boat_mesh(), dir + "/boat.stl");
  const auto r = run_strand("slice boat.stl --nozzle 0.6 --gap 1 --perimeters 1" + kMachine +
                                " -o b.gcode --report b.json",
                            dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("part 30.000 x 14.000 x 14.000 mm\n", 0), 0u) << "size first: " << r.out;
  EXPECT_NE(r.out.find("self-intersecting triangles resolved by contour union"),
            std::string::npos)
      << r.out;
  EXPECT_EQ(run_strand("check b.gcode" + kMachine, dir).exit_code, 0);
  const auto report = nlohmann::json::parse(slurp(dir + "/b.json"));
  // The hull, cabin and chimney layers are one region each: the union, no holes where they
  // overlap, so no more than 3 strands per layer.
  for (const auto& n : report.at("derived").at("regions_per_layer")) EXPECT_EQ(n.get<int>(), 1);
  for (const auto& n : report.at("derived").at("pattern_strands_per_layer"))
    EXPECT_LE(n.get<int>(), 3);
  EXPECT_EQ(report.at("totals").at("layers").get<std::size_t>(),
            report.at("derived").at("layers").get<std::size_t>());
}

TEST(SliceCli, ScaleToFitTakesTheLargestUniformScale) {
  const auto dir = fresh_dir("slice-fit");
  write_binary_stl(box_mesh(slicer::Vec3(10, 20, 5)), dir + "/box.stl");
  const auto r = run_strand(
      "slice box.stl --nozzle 0.6 --gap 1 --scale-to-fit 30x30x30 -o b.gcode --report b.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("part 15.000 x 30.000 x 7.500 mm\n", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("  scale          1.5\n"), std::string::npos) << r.out;
  const auto report = nlohmann::json::parse(slurp(dir + "/b.json"));
  EXPECT_NEAR(report.at("derived").at("scale").get<double>(), 1.5, 1e-12);
  EXPECT_EQ(report.at("parameters").at("scale-to-fit"), "30x30x30");
  const auto y_up =
      run_strand("slice box.stl --nozzle 0.6 --gap 1 --up y --scale 2 -o c.gcode", dir);
  ASSERT_EQ(y_up.exit_code, 0) << y_up.err;
  EXPECT_EQ(y_up.out.rfind("part 20.000 x 10.000 x 40.000 mm\n", 0), 0u) << "+Y up: " << y_up.out;
}

TEST(SliceCli, RealMeshSpotSlicesUpright) {
  // Keenan Crane's spot (CC0; source in tests/data/README.md): +Y up, unit size.
  const auto dir = fresh_dir("slice-spot");
  const std::string spot = std::string(STRAND_SOURCE_DIR) + "/samples/meshes/spot.obj";
  const auto r = run_strand(
      "slice " + spot + " --up y --scale-to-fit 30x30x30 --nozzle 0.6 --gap 1 --perimeters 1" +
          kMachine + " -o s.gcode --report s.json",
      dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(run_strand("check s.gcode" + kMachine, dir).exit_code, 0);
  const auto report = nlohmann::json::parse(slurp(dir + "/s.json"));
  const auto& size = report.at("derived").at("size_mm");
  const double x = size[0].get<double>(), y = size[1].get<double>(), z = size[2].get<double>();
  EXPECT_NEAR(std::max({x, y, z}), 30.0, 1e-9) << "the longest side fits the box exactly";
  EXPECT_GT(z, 1.5 * x) << "standing on its feet (+Y up turned to +Z), not lying on its side";
  EXPECT_EQ(report.at("totals").at("layers").get<std::size_t>(),
            report.at("derived").at("layers").get<std::size_t>());
}

TEST(MeshCli, InfoCountsDefectsAndRepairWritesAClosedMesh) {
  const auto dir = fresh_dir("mesh-info");
  slicer::Mesh open_box = box_mesh(slicer::Vec3(10, 10, 10));
  open_box.triangles.resize(10);  // one face gone: a square hole
  write_binary_stl(with_shell(open_box, box_mesh(slicer::Vec3(2, 2, 2)), slicer::Vec3(20, 0, 0)),
                   dir + "/open.stl");
  const auto info = run_strand("mesh open.stl --json", dir);
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const auto j = nlohmann::json::parse(info.out).at("info");
  EXPECT_EQ(j.at("triangles"), 22);
  EXPECT_EQ(j.at("shells"), 2);
  EXPECT_EQ(j.at("holes"), 1);
  EXPECT_EQ(j.at("border_edges"), 4);
  EXPECT_EQ(j.at("non_manifold_edges"), 0);
  EXPECT_TRUE(j.at("self_intersections").is_null()) << "not searched on an open mesh";
  const auto fixed = run_strand("mesh open.stl --repair -o fixed.stl", dir);
  ASSERT_EQ(fixed.exit_code, 0) << fixed.err;
  EXPECT_NE(fixed.out.find("  repaired       filled holes: 1"), std::string::npos) << fixed.out;
  const auto again = nlohmann::json::parse(run_strand("mesh fixed.stl --json", dir).out).at("info");
  EXPECT_EQ(again.at("holes"), 0);
  EXPECT_EQ(again.at("border_edges"), 0);
  EXPECT_EQ(again.at("self_intersections"), 0);
  EXPECT_NEAR(again.at("volume").get<double>(), 1008.0, 1e-3);
  expect_input_error(run_strand("mesh open.stl -o x.stl", dir), "add --repair");
  EXPECT_FALSE(exists(dir + "/x.stl"));
}

struct BadCase {
  const char* name;
  const char* args;
  const char* must_mention;
};

class SliceBadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(SliceBadInput, ExitTwoOneLineNoFile) {
  const auto dir = plug_dir();
  write_binary_stl(box_mesh(slicer::Vec3(0.5, 20, 5)), dir + "/fin.stl");
  write_binary_stl(box_mesh(slicer::Vec3(20, 20, 0.1)), dir + "/plate.stl");
  write_binary_stl(boat_mesh(), dir + "/boat.stl");
  slicer::write_file_atomic(dir + "/empty.stl", "");
  const auto r =
      run_strand(std::string("slice ") + GetParam().args + " -o out.gcode --report out.json", dir);
  expect_input_error(r, GetParam().must_mention);
  EXPECT_FALSE(exists(dir + "/out.gcode"));
  EXPECT_FALSE(exists(dir + "/out.json"));
}

INSTANTIATE_TEST_SUITE_P(
    Cases, SliceBadInput,
    ::testing::Values(
        BadCase{"missing_file", "nothere.stl --nozzle 0.6 --gap 1",
                "mesh = nothere.stl: no such file"},
        BadCase{"empty_file", "empty.stl --nozzle 0.6 --gap 1",
                "mesh = empty.stl: the file is empty"},
        BadCase{"rows", "plug.stl --pattern tetrachiral --nozzle 0.4 --cell 5 --rows 4",
                "tetrachiral.rows = 4: makes no sense for a sliced part"},
        BadCase{"size", "plug.stl --nozzle 0.6 --gap 1 --size 10x10",
                "scaffold.size = 10,10: makes no sense"},
        BadCase{"foreign_flag", "plug.stl --nozzle 0.6 --gap 1 --cell 5",
                "slice.cell: not a scaffold flag"},
        BadCase{"pattern", "plug.stl --pattern gyroid --nozzle 0.6",
                "slice.pattern = gyroid: must be one of"},
        BadCase{"too_big", "plug.stl --nozzle 0.6 --gap 1 --mesh-units m",
                "slice: the part (20000.000 x 20000.000 x 6000.000 mm"},
        BadCase{"too_big_scaled", "plug.stl --nozzle 0.6 --gap 1 --scale 30",
                "slice: the part (600.000 x 600.000 x 180.000 mm"},
        BadCase{"scale", "plug.stl --nozzle 0.6 --gap 1 --scale 0", "slice.scale = 0: must be in"},
        BadCase{"scale_nan", "plug.stl --nozzle 0.6 --gap 1 --scale nan", "slice.scale = nan"},
        BadCase{"fit", "plug.stl --nozzle 0.6 --gap 1 --scale-to-fit 30x30",
                "slice.scale-to-fit = 30x30"},
        BadCase{"fit_and_scale", "plug.stl --nozzle 0.6 --gap 1 --scale 2 --scale-to-fit 9x9x9",
                "give --scale or --scale-to-fit, not both"},
        BadCase{"up", "plug.stl --nozzle 0.6 --gap 1 --up x", "slice.up = x: must be z or y"},
        BadCase{"plate", "plate.stl --nozzle 0.6 --gap 1",
                "the part (20.000 x 20.000 x 0.100 mm) is thinner than one layer (nozzle 0.6 mm)"},
        BadCase{
            "narrow", "fin.stl --nozzle 1.2 --gap 2",
            "slice.nozzle = 1.2: the part (0.500 x 20.000 x 5.000 mm) is narrower than one bead"},
        BadCase{"strict", "boat.stl --nozzle 0.6 --gap 1 --strict", "boat.stl: self-intersecting"},
        BadCase{"units", "plug.stl --nozzle 0.6 --gap 1 --mesh-units ft", "slice.mesh-units = ft"},
        BadCase{"rotate", "plug.stl --nozzle 0.6 --gap 1 --rotate 90,0", "slice.rotate = 90,0"},
        BadCase{"layer_height", "plug.stl --nozzle 0.6 --gap 1 --layer-height 0.1",
                "scaffold.layer-height = 0.1"},
        BadCase{"perimeters", "plug.stl --nozzle 0.6 --gap 1 --perimeters 50",
                "slice.perimeters = 50"},
        BadCase{"plotter", "plug.stl --nozzle 0.6 --gap 1 --machine xy-plotter-servo",
                "a pen plotter; slice needs a printer"},
        BadCase{"robot_cell", "plug.stl --nozzle 0.6 --gap 1 --machine kuka-iiwa14-wasp-cylinder",
                "(robot-holds-substrate): slice and --onto need a 3-axis printer"},
        BadCase{"rotary", "plug.stl --nozzle 0.6 --gap 1 --machine marlin-rotary-a",
                "(rotary): slice and --onto need a 3-axis printer"},
        BadCase{"too_much_work", "plug.stl --nozzle 0.001 --pitch 0.001 --layer-height 0.001",
                "more work than allowed"}),
    [](const auto& info) { return std::string(info.param.name); });

// Keenan Crane's spot (CC0, a real scan-like mesh) on the screw extruder: the clipped pattern
// leaves slivers shorter than the output's 0.001 mm steps, which once became "G1 E0.00003"
// lines. Every G1 now moves an axis except the named prime and suck-back lines; --viewer-e
// writes its preview copy beside the file; the extent flags are listed for --onto only.
TEST(SliceCli, RealMeshHasNoAxislessMovesAndWritesViewerCopy) {
  const std::string dir = fresh_dir("slice-spot");
  const auto r = run_strand("slice " + std::string(STRAND_SOURCE_DIR) +
                                "/samples/meshes/spot.obj --up y --scale-to-fit 30x30x30 "
                                "--pattern scaffold --nozzle 0.6 --gap 1 --perimeters 1 "
                                "--machine deltawasp-2040-clay-ldm --viewer-e -o spot.gcode",
                            dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string g = slurp(dir + "/spot.gcode");
  std::istringstream lines(g);
  int moves = 0;
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("G1 ", 0) != 0) continue;
    ++moves;
    if (line.find(';') != std::string::npos) continue;  // "; prime", "; suck-back"
    EXPECT_TRUE(line.find(" X") != std::string::npos || line.find(" Y") != std::string::npos ||
                line.find(" Z") != std::string::npos)
        << line;
  }
  EXPECT_GT(moves, 1000);
  EXPECT_TRUE(exists(dir + "/spot.viewer-e.gcode"));
  EXPECT_EQ(run_strand("check spot.gcode", dir).exit_code, 0);
  const auto help = run_strand("slice --help", dir);
  EXPECT_NE(help.out.find("with --onto only: lattice footprint"), std::string::npos) << help.out;
}

}  // namespace
}  // namespace strand::testing
