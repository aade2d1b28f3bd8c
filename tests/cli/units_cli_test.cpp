// Forgiving input from the outside: values with units on the command line and in job files
// give the same files as plain numbers, paper names for --fit, choices in any case, and a
// unit of the wrong kind is one error line naming the parameter and the units it takes.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/support/cli_runner.h"

namespace strand::testing {
namespace {

const std::string kPlot = std::string(STRAND_SOURCE_DIR) + "/samples/plot/";

void write(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

TEST(UnitsCli, LengthsWithUnitsGiveTheSameGcodeAsMillimetres) {
  const auto dir = fresh_dir("units-length");
  const auto plain = run_strand(
      "scaffold --nozzle 0.84 --gap 1.6 --size 20x20 --height 3 --speed 600 -o plain.gcode", dir);
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  const auto units = run_strand(
      "scaffold --nozzle 840um --gap '0.16 cm' --size 2cmx20mm --height 3e-3m --speed 10mm/s "
      "-o units.gcode",
      dir);
  ASSERT_EQ(units.exit_code, 0) << units.err;
  EXPECT_EQ(slurp(dir + "/units.gcode"), slurp(dir + "/plain.gcode"));
  const auto spaced = run_strand(
      "scaffold --nozzle '8.4e-1 mm' --gap 1.6mm --size '20 x 20 mm' --height 3mm "
      "--speed '600 mm/min' -o spaced.gcode",
      dir);
  ASSERT_EQ(spaced.exit_code, 0) << spaced.err;
  EXPECT_EQ(slurp(dir + "/spaced.gcode"), slurp(dir + "/plain.gcode"));
}

TEST(UnitsCli, AnglesInRadiansAndDegrees) {
  const auto dir = fresh_dir("units-angle");
  ASSERT_EQ(run_strand("scaffold --nozzle 0.84 --gap 1.6 --size 20x20 --layers 2 --angles 0,90 "
                       "-o deg.gcode",
                       dir)
                .exit_code,
            0);
  const auto r = run_strand(
      "scaffold --nozzle 0.84 --gap 1.6 --size 20x20 --layers 2 --angles 0deg,90deg -o d2.gcode",
      dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(slurp(dir + "/d2.gcode"), slurp(dir + "/deg.gcode"));
}

TEST(UnitsCli, AWrongDimensionIsOneLineNamingTheExpectedUnits) {
  const auto dir = fresh_dir("units-wrong");
  const auto r = run_strand("scaffold --nozzle 3mm/s --gap 1.6 --size 20x20 --height 3 -o x.gcode", dir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "strand: error: scaffold.nozzle = 3mm/s: expected a length (mm, cm, m, um, in)\n");
  EXPECT_FALSE(exists(dir + "/x.gcode"));
  expect_input_error(
      run_strand("scaffold --nozzle 0.84 --gap 1.6 --size 20x20 --height 3 --speed 5mm", dir),
      "scaffold.speed = 5mm: expected a speed (mm/min, mm/s)");
  expect_input_error(
      run_strand("scaffold --nozzle 0.84 --gap 1.6 --size 20x20 --height 3 --angles 0,90mm", dir),
      "scaffold.angles = 0,90mm: expected an angle (deg, rad)");
  expect_input_error(run_strand("scaffold --nozzle 0.84 --gap 1.6 --size 20x20 --layers 3mm", dir),
                     "scaffold.layers = 3mm: expected a plain number (no unit)");
  expect_input_error(run_strand("scaffold --nozzle 0.84parsec --gap 1.6 --size 20x20 --layers 3", dir),
                     "scaffold.nozzle = 0.84parsec: expected a length (mm, cm, m, um, in)");
  EXPECT_FALSE(exists(dir + "/scaffold.gcode"));
}

TEST(UnitsCli, JobFileStringsMayCarryUnitsNumbersStayAsTheyAre) {
  const auto dir = fresh_dir("units-job");
  write(dir + "/plain.json", R"({"generator": "scaffold", "output": "plain.gcode",
      "params": {"nozzle": 0.84, "gap": 1.6, "size": [20, 20], "height": 3, "speed": 600}})");
  write(dir + "/units.json", R"({"generator": "scaffold", "output": "units.gcode",
      "params": {"nozzle": "0.84mm", "gap": "1600 um", "size": "20 x 20 mm", "height": "0.3cm",
                 "speed": "10mm/s"}})");
  ASSERT_EQ(run_strand("job plain.json", dir).exit_code, 0);
  const auto r = run_strand("job units.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(slurp(dir + "/units.gcode"), slurp(dir + "/plain.gcode"));
  write(dir + "/bad.json", R"({"generator": "scaffold", "output": "bad.gcode",
      "params": {"nozzle": "0.84mm/s", "gap": 1.6, "size": [20, 20], "height": 3}})");
  expect_input_error(run_strand("job bad.json", dir),
                     "scaffold.nozzle = 0.84mm/s: expected a length (mm, cm, m, um, in)");
  EXPECT_FALSE(exists(dir + "/bad.gcode"));
}

TEST(UnitsCli, FitTakesPaperNamesPortraitOrLandscape) {
  const auto dir = fresh_dir("units-paper");
  const std::string svg = "plot '" + kPlot + "shapes.svg' ";
  for (const auto& [paper, size] : std::vector<std::pair<std::string, std::string>>{
           {"A4", "210x297"}, {"'a4 landscape'", "297x210"}, {"A5-Landscape", "210x148"},
           {"letter", "215.9x279.4"}}) {
    const auto by_name = run_strand(svg + "--fit " + paper + " -o name.gcode --report name.json", dir);
    ASSERT_EQ(by_name.exit_code, 0) << paper << ": " << by_name.err;
    ASSERT_EQ(run_strand(svg + "--fit " + size + " -o size.gcode", dir).exit_code, 0);
    EXPECT_EQ(slurp(dir + "/name.gcode"), slurp(dir + "/size.gcode")) << paper;
    const auto report = nlohmann::json::parse(slurp(dir + "/name.json"));
    EXPECT_LT(report.dump().find("\"fit\""), std::string::npos) << paper;
  }
  const auto unknown = run_strand(svg + "--fit B5 -o b5.gcode", dir);
  expect_input_error(unknown, "plot.fit = B5: unknown paper (known: A0, A1, A2, A3, A4, A5, A6, "
                              "letter, legal, tabloid");
  EXPECT_FALSE(exists(dir + "/b5.gcode"));
}

TEST(UnitsCli, ChoicesInAnyCase) {
  const auto dir = fresh_dir("units-choices");
  const std::string svg = "plot '" + kPlot + "lettering.svg' --fit 150x100 ";
  ASSERT_EQ(run_strand(svg + "--text hershey --fill hatch -o lower.gcode", dir).exit_code, 0);
  const auto upper = run_strand(svg + "--text HERSHEY --fill Hatch -o upper.gcode", dir);
  ASSERT_EQ(upper.exit_code, 0) << upper.err;
  EXPECT_EQ(slurp(dir + "/upper.gcode"), slurp(dir + "/lower.gcode"));
  ASSERT_EQ(run_strand("scaffold --nozzle 0.84 --gap 1.6 --size 20x20 --layers 2 -o s.gcode", dir)
                .exit_code,
            0);
  const auto fdm = run_strand("check s.gcode --rules FDM", dir);
  const auto lower = run_strand("check s.gcode --rules fdm", dir);
  EXPECT_EQ(fdm.exit_code, 0) << fdm.err;
  EXPECT_EQ(fdm.out, lower.out);
  EXPECT_NE(fdm.out.find("rules fdm"), std::string::npos) << fdm.out;
  const auto view = run_strand("preview s.gcode --view TOP --colour Layer -o top.png", dir);
  EXPECT_EQ(view.exit_code, 0) << view.err;
  expect_input_error(run_strand(svg + "--text gothic -o g.gcode", dir),
                     "plot.text = gothic: must be one of hershey, outline, none");
}

// Flags outside the parameter tables take units too: slice's --rotate, --scale-to-fit and
// --arc-tolerance, preview's --size, flow's lengths and speed.
TEST(UnitsCli, FlagsOutsideTheTablesTakeUnits) {
  const auto dir = fresh_dir("units-flags");
  const std::string mesh = std::string(STRAND_SOURCE_DIR) + "/samples/meshes/sphere-cap.stl";
  const std::string slice = "slice '" + mesh + "' --nozzle 0.6 --gap 1 ";
  const auto plain = run_strand(slice + "--scale-to-fit 30x30x10 --rotate 0,0,90 --arc-tolerance 0.02 -o plain.gcode", dir);
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  const auto units = run_strand(slice + "--scale-to-fit '3 x 3 x 1 cm' --rotate '0,0,1.5707963267948966rad' "
                                        "--arc-tolerance 20um -o units.gcode", dir);
  ASSERT_EQ(units.exit_code, 0) << units.err;
  // Only the echoed parameters differ.
  const auto strip = [](std::string g) {
    std::string out;
    std::size_t at = 0;
    while (at < g.size()) {
      const std::size_t end = std::min(g.find('\n', at), g.size());
      const std::string line = g.substr(at, end - at);
      if (line.rfind("; param rotate", 0) != 0 && line.rfind("; param scale-to-fit", 0) != 0) out += line + "\n";
      at = end + 1;
    }
    return out;
  };
  const std::string a = slurp(dir + "/plain.gcode");
  EXPECT_GT(a.size(), 1000u);
  EXPECT_EQ(strip(slurp(dir + "/units.gcode")), strip(a));
  expect_input_error(run_strand(slice + "--rotate 0,0,1mm -o x.gcode", dir),
                     "slice.rotate = 0,0,1mm: must be X,Y,Z in degrees, each in [-360, 360] (expected an angle (deg, rad))");
  expect_input_error(run_strand(slice + "--arc-tolerance 3mm/s -o x.gcode", dir),
                     "--arc-tolerance = 3mm/s: expected a length (mm, cm, m, um, in)");
  EXPECT_FALSE(exists(dir + "/x.gcode"));

  const auto px = run_strand("preview plain.gcode --size '400 x 300 px' --view top -o px.png", dir);
  ASSERT_EQ(px.exit_code, 0) << px.err;
  const auto bare = run_strand("preview plain.gcode --size 400x300 --view top -o bare.png", dir);
  ASSERT_EQ(bare.exit_code, 0) << bare.err;
  EXPECT_EQ(slurp(dir + "/px.png"), slurp(dir + "/bare.png"));
  expect_input_error(run_strand("preview plain.gcode --size 400mmx300mm -o mm.png", dir),
                     "--size = 400mmx300mm: must be WxH in whole pixels, each in [1, 100000], e.g. 1200x700");

  const std::string flow = "flow --viscosity-pa-s 10 ";
  const auto mm = run_strand(flow + "--nozzle-mm 0.84 --nozzle-length-mm 12.7 --speed 300", dir);
  const auto si = run_strand(flow + "--nozzle-mm 840um --nozzle-length-mm 0.5in --speed 5mm/s", dir);
  ASSERT_EQ(mm.exit_code, 0) << mm.err;
  EXPECT_EQ(si.out, mm.out);
  expect_input_error(run_strand(flow + "--nozzle-mm 3mm/s --nozzle-length-mm 12 --speed 5", dir),
                     "--nozzle-mm = 3mm/s: expected a length (mm, cm, m, um, in)");
}

}  // namespace
}  // namespace strand::testing
