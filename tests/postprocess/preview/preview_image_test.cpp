// PNG and SVG previews: drawn area of a known square, layer filter, colouring, bad options.
#include "postprocess/preview/preview_image.h"

#include <gtest/gtest.h>

#include "postprocess/inspect/gcode_parser.h"
#include "slicer/input_error.h"
#include "tests/support/png_pixels.h"

namespace strand::post {
namespace {

// A 20 mm square outline drawn with a 1 mm bead on layer 0, and a 10 mm one on layer 1.
const char* kSquares =
    ";LAYER:0\nG0 X0 Y0 Z0.5\n;WIDTH:1\nG1 X20 Y0 E1\nG1 X20 Y20 E2\nG1 X0 Y20 E3\nG1 X0 Y0 E4\n"
    ";LAYER:1\nG0 X5 Y5 Z1\nG1 X15 Y5 E5\nG1 X15 Y15 E6\nG1 X5 Y15 E7\nG1 X5 Y5 E8\n";

PreviewScene squares() { return preview_scene(parse_gcode(kSquares).program, 0.01); }

ImageOptions known_scale(int layer) {
  ImageOptions o;
  o.width_px = 400;
  o.height_px = 400;
  o.view = PreviewView::Top;
  o.layer = layer;
  o.scale_bar = false;
  o.px_per_mm = 10.0;
  return o;
}

TEST(PreviewImage, SquareCoversItsBeadArea) {
  // Ring of 21^2 - 19^2 = 80 mm^2 at 100 px/mm^2 in a 400 x 400 image: 5 %.
  const auto st = strand::testing::png_stats(render_png(squares(), known_scale(0)));
  ASSERT_EQ(st.width, 400);
  EXPECT_NEAR(st.drawn_fraction, 0.05, 0.004);
}

TEST(PreviewImage, AllLayersDrawMoreThanOne) {
  const double one = strand::testing::png_stats(render_png(squares(), known_scale(0))).drawn_fraction;
  const double all = strand::testing::png_stats(render_png(squares(), known_scale(-1))).drawn_fraction;
  // The inner square (40 mm^2 of bead) adds about 2.5 %.
  EXPECT_NEAR(all - one, 0.025, 0.004);
}

TEST(PreviewImage, ScaleBarAndCaptionAddInk) {
  ImageOptions o = known_scale(0);
  const double without = strand::testing::png_stats(render_png(squares(), o)).drawn_fraction;
  o.scale_bar = true;
  EXPECT_GT(strand::testing::png_stats(render_png(squares(), o)).drawn_fraction, without);
}

TEST(PreviewImage, LayerColouringDiffersFromFeatureColouring) {
  ImageOptions o = known_scale(-1);
  const std::string by_feature = render_png(squares(), o);
  o.colouring = PreviewColouring::Layer;
  EXPECT_NE(render_png(squares(), o), by_feature);
}

TEST(PreviewImage, SvgIsVectorWithTheSameView) {
  const std::string svg = render_svg(squares(), known_scale(-1));
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_NE(svg.find("<path"), std::string::npos);
  EXPECT_NE(svg.find("width=\"400pt\""), std::string::npos);
}

// Layer 0 crosses itself at (5, 5); layer 1 is one straight line.
const char* kCrossing =
    ";LAYER:0\nG0 X0 Y0 Z0.5\n;WIDTH:1\nG1 X10 Y10 E1\nG1 X10 Y0 E2\nG1 X0 Y10 E3\n"
    ";LAYER:1\nG0 X0 Y0 Z1\nG1 X20 Y0 E4\n";

TEST(PreviewImage, MarksCircleTheCheckedCrossingInRed) {
  const ParsedGcode parsed = parse_gcode(kCrossing);
  const auto marks = marks_from(check_parsed(parsed, {}));
  ASSERT_EQ(marks.size(), 1u);
  EXPECT_TRUE(marks[0].crossing);
  EXPECT_NEAR(marks[0].at_mm.x(), 5.0, 1e-9);
  const PreviewScene scene = preview_scene(parsed.program, 0.01);
  ImageOptions o = known_scale(0);
  const auto red = [&] { return strand::testing::colour_spot(render_png(scene, o), 224, 0, 0, 40); };
  EXPECT_EQ(red().count, 0) << "no marks unless asked";
  o.marks = marks;
  const auto spot = red();
  ASSERT_GT(spot.count, 20);
  // 10 px/mm, the scene (x 0..20, y 0..10 over both layers) centred: (5, 5) is 50 px left.
  EXPECT_NEAR(spot.x_px, 150.0, 1.5);
  EXPECT_NEAR(spot.y_px, 200.0, 1.5);
  o.layer = 1;
  EXPECT_EQ(red().count, 0) << "marks of other layers are not drawn";
}

TEST(PreviewImage, SameSceneSameBytes) {
  EXPECT_EQ(render_png(squares(), known_scale(-1)), render_png(squares(), known_scale(-1)));
}

TEST(PreviewImage, LayerOutsideTheFileIsAnInputError) {
  try {
    render_png(squares(), known_scale(2));
    FAIL() << "accepted layer 2";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("layer = 2: must be in [0, 1]"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace strand::post
