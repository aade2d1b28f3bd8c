// Several printheads end to end through the `strand` binary (issue 33): a two-head machine
// profile, nodes and ligaments of a tetrachiral specimen in different inks by --tools or a
// job file, the G-code's tool changes and offsets, E per head, and check's strands per head.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tests/support/cli_runner.h"

namespace strand::testing {
namespace {

// Two screw heads, the second 40 mm right of the first and its nozzle 0.5 mm lower.
constexpr char kTwoScrews[] = R"({
  "name": "two-screws", "description": "two E-driven heads",
  "kinematics": {"type": "cartesian", "min_mm": [0, 0, 0], "max_mm": [200, 200, 100], "part_center_mm": [100, 100]},
  "firmware": {"flavour": "marlin", "arcs": false},
  "deposition": {"model": "e-volumetric", "mm3_per_e": 1.0, "relative_e": true},
  "tools": [{"name": "soft", "deselect_gcode": ["M42 P9 S0 ; {name} idle"]},
            {"name": "stiff", "offset_mm": [40, 0, -0.5], "temperature_c": 37, "select_gcode": ["M117 prime {name}"],
             "deposition": {"model": "e-volumetric", "mm3_per_e": 2.0, "relative_e": true}}]})";

constexpr char kParams[] = "--nozzle 0.5 --cell 10 --cols 2 --rows 2 --layers 2 --grip 5";

TEST(MultiToolCli, NodesAndLigamentsInTwoHeadsWithTheirOffsetsAndTheirOwnE) {
  const auto dir = fresh_dir("multi-tool");
  std::ofstream(dir + "/two-screws.json") << kTwoScrews;
  auto r = run_strand(std::string("tetrachiral ") + kParams +
                          " --machine two-screws.json --tools node=1,ligament=0,frame=0,grip=0 -o t.gcode --report t.json",
                      dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("tools          0 (soft)"), std::string::npos) << r.out;
  const auto report = nlohmann::json::parse(slurp(dir + "/t.json"));
  const auto& tools = report["totals"]["tools"];
  ASSERT_EQ(tools.size(), 2u);

  // Walk the file: per head the E it pushes and where its deposits lie.
  std::istringstream in(slurp(dir + "/t.gcode"));
  std::string line;
  int tool = -1, changes = 0;
  std::map<int, double> e;
  std::map<int, double> x_min, x_max;
  double z_t0 = -1, z_t1 = -1, z = 0;
  while (std::getline(in, line)) {
    if (line.starts_with("T")) {
      tool = std::stoi(line.substr(1));
      ++changes;
      continue;
    }
    if (!line.starts_with("G1 ") && !line.starts_with("G0 ")) continue;
    std::istringstream words(line.substr(3));
    std::string w;
    double de = 0;
    std::optional<double> x;
    while (words >> w) {
      if (w[0] == ';') break;
      if (w[0] == 'E') de = std::stod(w.substr(1));
      if (w[0] == 'X') x = std::stod(w.substr(1));
      if (w[0] == 'Z') z = std::stod(w.substr(1));
    }
    if (de <= 0 || tool < 0) continue;
    e[tool] += de;
    (tool == 0 ? z_t0 : z_t1) = z;
    if (x) {
      x_min[tool] = x_min.count(tool) ? std::min(x_min[tool], *x) : *x;
      x_max[tool] = x_max.count(tool) ? std::max(x_max[tool], *x) : *x;
    }
  }
  EXPECT_GE(changes, 2);
  // The head warms from the start; a change to it waits for it, after the last head idles.
  const std::string gcode = slurp(dir + "/t.gcode");
  EXPECT_NE(gcode.find("M104 T1 S37 ; stiff\n"), std::string::npos);
  EXPECT_NE(gcode.find("M42 P9 S0 ; soft idle\nM109 T1 S37 ; wait for stiff\nT1\nM117 prime stiff\n"), std::string::npos);
  // E per head is that head's ink over its own mm3 per E.
  EXPECT_NEAR(e[0], tools[0]["ink_volume_mm3"].get<double>() / 1.0, 0.01 * e[0]);
  EXPECT_NEAR(e[1], tools[1]["ink_volume_mm3"].get<double>() / 2.0, 0.01 * e[1]);
  // The specimen is centred at x = 100: head 2's carriage goes 40 mm left and 0.5 mm higher.
  EXPECT_GT(x_min[0], 85.0);
  EXPECT_LT(x_max[1], 75.0);
  EXPECT_NEAR(z_t1 - z_t0, 0.5, 1e-3) << "the last layer of each head";

  // Read back through the offsets the file names: no crossing, strands per head.
  const auto c = run_strand("check t.gcode --json", dir);
  ASSERT_EQ(c.exit_code, 0) << c.out;
  const auto check = nlohmann::json::parse(c.out);
  EXPECT_TRUE(check["ok"].get<bool>());
  EXPECT_EQ(check["crossings"], 0);
  ASSERT_TRUE(check["layers"][0].contains("strands_by_tool")) << check["layers"][0].dump();
  EXPECT_EQ(check["layers"][0]["strands_by_tool"].size(), 2u);
  EXPECT_GT(check["layers"][0]["strands_by_tool"][1].get<int>(), 0);

  // A job file's "tools" gives the same bytes as the flag.
  std::ofstream(dir + "/job.json") << R"({"generator": "tetrachiral", "machine": "two-screws.json",
      "params": {"nozzle": 0.5, "cell": 10, "cols": 2, "rows": 2, "layers": 2, "grip": 5},
      "tools": {"by_feature": {"node": 1, "ligament": 0, "frame": 0, "grip": 0}}})";
  ASSERT_EQ(run_strand("job job.json -o j.gcode", dir).exit_code, 0);
  EXPECT_EQ(slurp(dir + "/j.gcode"), slurp(dir + "/t.gcode"));
}

// A sliced part's perimeters in one head's ink, its fill in the other's.
TEST(MultiToolCli, SliceTakesToolsByFeature) {
  const auto dir = fresh_dir("multi-tool-slice");
  std::ofstream(dir + "/two-screws.json") << kTwoScrews;
  const std::string mesh = std::string(STRAND_SOURCE_DIR) + "/samples/meshes/bone-plug.stl";
  auto r = run_strand("slice " + mesh + " --pattern scaffold --nozzle 0.5 --gap 1 --perimeters 1 --machine two-screws.json"
                      " --tools wall=1,infill=0 -o plug.gcode --report plug.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(slurp(dir + "/plug.json"))["tools"], "wall=1,infill=0");
  const auto check = nlohmann::json::parse(run_strand("check plug.gcode --json", dir).out);
  EXPECT_EQ(check["crossings"], 0);
  for (const auto& layer : check["layers"]) {
    ASSERT_EQ(layer["strands_by_tool"].size(), 2u) << layer.dump();
    EXPECT_GE(layer["strands_by_tool"][1].get<int>(), 2) << "the outer and the hole's perimeter";
  }
  expect_input_error(run_strand("slice " + mesh + " --pattern scaffold --nozzle 0.5 --gap 1 --tools wall=1 -o x.gcode", dir),
                     "slice.tools = wall=1: tool 1 is not on machine deltawasp-2040-clay");
  EXPECT_FALSE(exists(dir + "/x.gcode"));
}

TEST(MultiToolCli, ALayerCycleAndTheRefusals) {
  const auto dir = fresh_dir("multi-tool-bad");
  std::ofstream(dir + "/two-screws.json") << kTwoScrews;
  auto r = run_strand("scaffold --nozzle 0.5 --gap 1 --size 10x10 --layers 4 --machine two-screws.json --tools layers=0,1 -o s.gcode", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("3 change(s)"), std::string::npos) << r.out;
  expect_input_error(run_strand("scaffold --nozzle 0.5 --gap 1 --size 10x10 --layers 2 --machine two-screws.json --tools layers=0,2 -o x.gcode", dir),
                     "tools = layers=0,2: tool 2 is not on machine two-screws (2 tool(s): 0 to 1)");
  EXPECT_FALSE(exists(dir + "/x.gcode"));
  expect_input_error(run_strand("scaffold --nozzle 0.5 --gap 1 --size 10x10 --layers 2 --tools node=1 -o x.gcode", dir),
                     "tool 1 is not on machine deltawasp-2040-clay (1 tool(s): 0 to 0)");
  expect_input_error(run_strand("scaffold --nozzle 0.5 --gap 1 --size 10x10 --layers 2 --tools wing=1 -o x.gcode", dir),
                     "wing is not a feature");
  EXPECT_FALSE(exists(dir + "/x.gcode"));
}

}  // namespace
}  // namespace strand::testing
