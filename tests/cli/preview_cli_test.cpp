// `strand preview` from the outside: every extension from one G-code, bad input.
#include <gtest/gtest.h>

#include <fstream>

#include "tests/support/cli_runner.h"
#include "tests/support/png_pixels.h"

namespace strand::testing {
namespace {

const std::string kScaffold = "scaffold --nozzle 0.84 --gap 1.6 --size 20x20 --height 3 -o s.gcode --report s.json";

TEST(PreviewCli, WritesEachFormatFromAnyGcode) {
  const auto dir = fresh_dir("preview");
  ASSERT_EQ(run_strand(kScaffold, dir).exit_code, 0);
  for (const char* ext : {"png", "svg", "html", "glb"}) {
    const auto r = run_strand(std::string("preview s.gcode -o p.") + ext, dir);
    EXPECT_EQ(r.exit_code, 0) << r.err;
  }
  const auto png = png_stats(slurp(dir + "/p.png"));
  EXPECT_EQ(png.width, 1200);
  EXPECT_GT(png.drawn_fraction, 0.05);
  EXPECT_NE(slurp(dir + "/p.svg").find("<svg"), std::string::npos);
  EXPECT_EQ(slurp(dir + "/p.glb").substr(0, 4), "glTF");
}

TEST(PreviewCli, OneLayerDrawsLessThanAll) {
  const auto dir = fresh_dir("preview-layer");
  ASSERT_EQ(run_strand(kScaffold, dir).exit_code, 0);
  ASSERT_EQ(run_strand("preview s.gcode -o all.png --view top", dir).exit_code, 0);
  ASSERT_EQ(run_strand("preview s.gcode -o one.png --view top --layer 0", dir).exit_code, 0);
  EXPECT_LT(png_stats(slurp(dir + "/one.png")).drawn_fraction, png_stats(slurp(dir + "/all.png")).drawn_fraction);
}

TEST(PreviewCli, MarksCircleCrossingsAndCheckDrawsTheSameLayerView) {
  const auto dir = fresh_dir("preview-marks");
  std::ofstream(dir + "/x.gcode") << ";LAYER:0\nG0 X0 Y0 Z0.5\nG1 X10 Y10 E1\nG1 X10 Y0 E2\nG1 X0 Y10 E3\n";
  ASSERT_EQ(run_strand("preview x.gcode -o plain.png --view top", dir).exit_code, 0);
  ASSERT_EQ(run_strand("preview x.gcode -o marked.png --view top --marks", dir).exit_code, 0);
  EXPECT_EQ(colour_spot(slurp(dir + "/plain.png"), 224, 0, 0, 40).count, 0);
  EXPECT_GT(colour_spot(slurp(dir + "/marked.png"), 224, 0, 0, 40).count, 20);
  // `check --svg-layer` is the preview's top view of that layer with travels and marks.
  EXPECT_EQ(run_strand("check x.gcode --svg-layer 0 check.svg", dir).exit_code, 1);
  ASSERT_EQ(run_strand("preview x.gcode -o view.svg --view top --layer 0 --travel --marks", dir).exit_code, 0);
  EXPECT_EQ(slurp(dir + "/check.svg"), slurp(dir + "/view.svg"));
}

struct BadCase {
  const char* name;
  const char* args;
  const char* must_mention;
};

class PreviewBadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(PreviewBadInput, ExitTwoOneLineNoFile) {
  const auto dir = fresh_dir("preview-bad");
  ASSERT_EQ(run_strand(kScaffold, dir).exit_code, 0);
  const auto r = run_strand(GetParam().args, dir);
  expect_input_error(r, GetParam().must_mention);
  EXPECT_FALSE(exists(dir + "/out.png"));
}

INSTANTIATE_TEST_SUITE_P(
    Cases, PreviewBadInput,
    ::testing::Values(
        BadCase{"unreadable", "preview missing.gcode -o out.png", "input = missing.gcode: no such file"},
        BadCase{"not_gcode", "preview s.json -o out.png", "input = s.json: no moves"},
        BadCase{"extension", "preview s.gcode -o out.bmp", "--output = out.bmp"},
        BadCase{"layer", "preview s.gcode -o out.png --layer 99", "layer = 99"},
        BadCase{"view", "preview s.gcode -o out.png --view side", "--view = side"},
        BadCase{"size", "preview s.gcode -o out.png --size 0x10", "--size = 0x10"}),
    [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace strand::testing
