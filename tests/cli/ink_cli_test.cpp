// Ink development end to end through the `strand` binary: line-matrix -> photo -> measure ->
// calibrate -> a scaffold printed with --material; and the one-line refusals on the way.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "machines/profile.h"
#include "postprocess/measure/photo.h"
#include "slicer/file_io.h"
#include "tests/postprocess/measure/synthetic_photo.h"
#include "tests/support/cli_runner.h"

namespace strand::testing {
namespace {

nlohmann::json read_json(const std::string& path) { return nlohmann::json::parse(slurp(path)); }

TEST(InkCli, LineMatrixPassesCheckOnEveryFlatPrinter) {
  int checked = 0;
  for (const auto& [name, description] : machines::list_profiles()) {
    const auto m = machines::load_profile(name);
    if (m.plotter.enabled || m.robot.enabled || m.rotary.enabled) continue;
    SCOPED_TRACE(name);
    const auto dir = fresh_dir("ink-check");
    const auto r = run_strand("line-matrix --nozzle 0.6 --machine " + name + " -o lm.gcode", dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto c = run_strand("check lm.gcode --machine " + name + " --json", dir);
    const auto j = nlohmann::json::parse(c.out);
    EXPECT_TRUE(j["ok"].get<bool>()) << c.out.substr(0, 2000);
    EXPECT_EQ(j["crossings"], 0);
    ++checked;
  }
  EXPECT_GE(checked, 4);
}

TEST(InkCli, PrintPhotographMeasureCalibrateThenPrintWithTheMaterial) {
  const auto dir = fresh_dir("ink-loop");
  auto r = run_strand("line-matrix --nozzle 0.6 --report lm.json -o lm.gcode", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto report = read_json(dir + "/lm.json");
  slicer::write_file_atomic(dir + "/photo.png", post::measure::encode_png(synthetic_photo(report["derived"], law_width)));

  r = run_strand("measure photo.png --test lines --job lm.json -o m.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("16 lines"), std::string::npos) << r.out;
  ASSERT_TRUE(exists(dir + "/m.png"));
  const auto m = read_json(dir + "/m.json");
  ASSERT_EQ(m["lines"].size(), 16u);
  for (const auto& l : m["lines"]) {
    const double truth = law_width(l);
    EXPECT_NEAR(l["width_mm"].get<double>(), truth, 0.05 * truth) << l.dump();
  }

  std::filesystem::create_directories(dir + "/materials");
  r = run_strand("calibrate m.json -o materials/test-ink.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto ink = read_json(dir + "/materials/test-ink.json");
  EXPECT_NEAR(ink["width_model"]["p"].get<double>(), 0.6, 0.03);
  EXPECT_NEAR(ink["width_model"]["q"].get<double>(), -0.4, 0.02);
  EXPECT_EQ(ink["measurements"], nlohmann::json::array({"m.json"}));

  // The profile's speed and layer height, unless given; the report says where they came from.
  r = run_strand("scaffold --nozzle 0.6 --gap 1 --size 10x10 --layers 2 --material test-ink --report s.json -o s.gcode", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto s = read_json(dir + "/s.json");
  EXPECT_EQ(s["parameters"]["speed"], ink["print"]["speed_mm_min"]);
  EXPECT_EQ(s["parameters"]["layer-height"], ink["print"]["layer_height_mm"]);
  EXPECT_EQ(s["material"]["name"], "test-ink");
  EXPECT_EQ(s["material"]["measurements"], nlohmann::json::array({"m.json"}));
  r = run_strand("scaffold --nozzle 0.6 --gap 1 --size 10x10 --layers 2 --speed 123 --material test-ink --report s2.json -o s2.gcode", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_json(dir + "/s2.json")["parameters"]["speed"], 123);
}

// A job file names its ink as --material does; the flow the profile holds reaches the machine:
// E times the flow on a screw extruder, a pause to set it on the manual valve.
TEST(InkCli, AJobFilesMaterialSetsSpeedLayerHeightAndFlow) {
  const auto dir = fresh_dir("ink-job");
  std::filesystem::create_directories(dir + "/materials");
  std::ofstream(dir + "/materials/paste.json")
      << R"({"name": "paste", "nozzle_mm": 0.6, "measurements": ["m.json"],
             "print": {"speed_mm_min": 320, "flow": 1.2, "layer_height_mm": 0.5}})";
  const std::string params = R"("params": {"nozzle": 0.6, "gap": 1, "size": "10x10", "layers": 2})";
  std::ofstream(dir + "/ink.json") << R"({"generator": "scaffold", "machine": "deltawasp-2040-clay-ldm", "material": "paste", )"
                                   << params << "}";
  std::ofstream(dir + "/plain.json") << R"({"generator": "scaffold", "machine": "deltawasp-2040-clay-ldm",
      "params": {"nozzle": 0.6, "gap": 1, "size": "10x10", "layers": 2, "speed": 320, "layer-height": 0.5}})";
  auto r = run_strand("job ink.json --report ink-report.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto report = read_json(dir + "/ink-report.json");
  EXPECT_EQ(report["parameters"]["speed"], 320);
  EXPECT_EQ(report["parameters"]["layer-height"], 0.5);
  EXPECT_EQ(report["material"]["flow"], 1.2);
  ASSERT_EQ(run_strand("job plain.json --report plain-report.json", dir).exit_code, 0);
  const double ink_mm3 = report["totals"]["ink_volume_mm3"].get<double>();
  const double plain_mm3 = read_json(dir + "/plain-report.json")["totals"]["ink_volume_mm3"].get<double>();
  EXPECT_NEAR(ink_mm3, 1.2 * plain_mm3, 0.002);

  std::ofstream(dir + "/manual.json") << R"({"generator": "scaffold", "material": "paste", )" << params << "}";
  ASSERT_EQ(run_strand("job manual.json -o manual.gcode", dir).exit_code, 0);
  const std::string gcode = slurp(dir + "/manual.gcode");
  EXPECT_NE(gcode.find("M117 Set flow 1.2 for this ink, then resume\nM0 "), std::string::npos);
  EXPECT_EQ(run_strand("check manual.gcode", dir).exit_code, 0);

  std::ofstream(dir + "/missing.json") << R"({"generator": "scaffold", "material": "nothing", )" << params << "}";
  expect_input_error(run_strand("job missing.json -o missing.gcode", dir), "material = nothing");
  EXPECT_FALSE(exists(dir + "/missing.gcode"));
}

TEST(InkCli, BadPhotosAndBadInputAreOneLineAndWriteNothing) {
  const auto dir = fresh_dir("ink-bad");
  ASSERT_EQ(run_strand("line-matrix --nozzle 0.6 --report lm.json -o lm.gcode", dir).exit_code, 0);
  const auto report = read_json(dir + "/lm.json");
  PhotoSetup no_marks;
  no_marks.draw_marks = false;
  slicer::write_file_atomic(dir + "/bare.png", post::measure::encode_png(synthetic_photo(report["derived"], law_width, no_marks)));
  auto r = run_strand("measure bare.png --test lines --job lm.json -o m.json", dir);
  expect_input_error(r, "found 0 of the 4 fiducial marks");
  EXPECT_FALSE(exists(dir + "/m.json"));
  EXPECT_FALSE(exists(dir + "/m.png"));

  slicer::write_file_atomic(dir + "/photo.png", post::measure::encode_png(synthetic_photo(report["derived"], law_width)));
  expect_input_error(run_strand("measure photo.png --test pore --job lm.json -o m.json", dir), "measure.test = pore");
  // -o photo.json would put the overlay on photo.png: refused, the photo kept.
  const std::string photo_bytes = slurp(dir + "/photo.png");
  expect_input_error(run_strand("measure photo.png --test lines --job lm.json -o photo.json", dir),
                     "measure.overlay = photo.png: would overwrite an input");
  EXPECT_EQ(slurp(dir + "/photo.png"), photo_bytes);
  std::ofstream(dir + "/s.json") << R"({"derived": {"footprint_mm": [36, 36]}})";
  expect_input_error(run_strand("measure photo.png --test lines --job s.json -o m.json", dir), "not a line-matrix report");
  // A PNG header that claims ten gigapixels is refused before anything is decoded.
  std::ofstream(dir + "/huge.png", std::ios::binary)
      << std::string("\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR\0\x01\x86\xa0\0\x01\x86\xa0\x08\x02\0\0\0" "\0\0\0\0", 33);
  expect_input_error(run_strand("measure huge.png --test lines --job lm.json -o m.json", dir), "60 megapixels");
  EXPECT_FALSE(exists(dir + "/m.json"));

  expect_input_error(run_strand("scaffold --nozzle 0.6 --gap 1 --size 10x10 --layers 2 --material nothing -o x.gcode", dir),
                     "material = nothing");
  EXPECT_FALSE(exists(dir + "/x.gcode"));
  expect_input_error(run_strand("line-matrix --nozzle 0.6 --spacing 1 -o y.gcode", dir), "line-matrix.spacing = 1: must be >= 2.4");
  EXPECT_FALSE(exists(dir + "/y.gcode"));
  expect_input_error(run_strand("calibrate lm.json -o ink.json", dir), "not a `strand measure --test lines` output");
  EXPECT_FALSE(exists(dir + "/ink.json"));
}

}  // namespace
}  // namespace strand::testing
