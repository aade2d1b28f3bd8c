// `strand slice` from the outside: every pattern on a part with a hole passes
// `strand check --machine`; bad meshes and flags exit 2 with one line and no file.
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "slicer/file_io.h"
#include "tests/support/cli_runner.h"
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
  expect_input_error(run_strand("slice plug.stl --nozzle 0.6 --gap 1 -o q.gcode --preview q.bmp", dir),
                     "slice.preview = q.bmp: extension must be");
  EXPECT_FALSE(exists(dir + "/q.gcode"));
}

TEST(SliceCli, RepairMakesAHoledMeshSlice) {
  const auto dir = fresh_dir("slice-repair");
  slicer::Mesh m = tube_mesh(8.0, 0.0, 4.0, 48);
  m.triangles.pop_back();
  write_binary_stl(m, dir + "/holed.stl");
  const auto bad = run_strand("slice holed.stl --nozzle 0.6 --gap 1 -o h.gcode", dir);
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

struct BadCase {
  const char* name;
  const char* args;
  const char* must_mention;
};

class SliceBadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(SliceBadInput, ExitTwoOneLineNoFile) {
  const auto dir = plug_dir();
  write_binary_stl(box_mesh(slicer::Vec3(0.5, 20, 5)), dir + "/fin.stl");
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
                "slice: the part (20000 x 20000 x 6000 mm"},
        BadCase{"units", "plug.stl --nozzle 0.6 --gap 1 --mesh-units ft", "slice.mesh-units = ft"},
        BadCase{"rotate", "plug.stl --nozzle 0.6 --gap 1 --rotate 90,0", "slice.rotate = 90,0"},
        BadCase{"thin_wall", "fin.stl --nozzle 0.84 --gap 1", "wider than the part's wall near"},
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

}  // namespace
}  // namespace strand::testing
