// PNG and SVG previews: drawn area of a known square, layer filter, colouring, bad options.
#include "postprocess/preview/preview_image.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "postprocess/inspect/gcode_parser.h"
#include "slicer/input_error.h"
#include "tests/support/cylinder_scene.h"
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

// Byte colour of a feature, for colour_spot.
std::array<int, 3> rgb_of(slicer::Feature f) {
  const Rgb c = feature_colour(f);
  auto b = [](double v) { return static_cast<int>(std::lround(v * 255)); };
  return {b(c.r), b(c.g), b(c.b)};
}

long pixels_of(const std::string& png, slicer::Feature f, strand::testing::PxBox box = {}) {
  const auto c = rgb_of(f);
  return strand::testing::colour_spot(png, c[0], c[1], c[2], 30, box).count;
}

TEST(PreviewImage, LegendShowsTheFeaturesDrawnWithTheCaption) {
  ImageOptions o = known_scale(0);  // the square sits at 100..300 px, clear of the top rows
  const strand::testing::PxBox top_rows{0, 0, 400, 22};
  EXPECT_EQ(pixels_of(render_png(squares(), o), slicer::Feature::Infill, top_rows), 0);
  o.scale_bar = true;
  const std::string png = render_png(squares(), o);
  EXPECT_GT(pixels_of(png, slicer::Feature::Infill, top_rows), 80) << "an 11 x 11 px swatch";
  EXPECT_EQ(pixels_of(png, slicer::Feature::Wall, top_rows), 0) << "only features drawn";
}

TEST(PreviewImage, IsometricViewIsNotMirrored) {
  // x to the lower right, y to the upper right: a right-handed view from (1, -1, 1)
  const char* kAxes = ";LAYER:0\n;Z:0\nG0 X0 Y0 Z0\n;WIDTH:1\n;FEATURE:wall\nG1 X20 Y0 E1\n"
                      "G0 X0 Y0\n;FEATURE:infill\nG1 X0 Y20 E2\n";
  ImageOptions o = known_scale(0);
  o.view = PreviewView::Iso;
  const std::string png = render_png(preview_scene(parse_gcode(kAxes).program, 0.01), o);
  const auto wall = rgb_of(slicer::Feature::Wall), infill = rgb_of(slicer::Feature::Infill);
  const auto x_axis = strand::testing::colour_spot(png, wall[0], wall[1], wall[2], 30);
  const auto y_axis = strand::testing::colour_spot(png, infill[0], infill[1], infill[2], 30);
  ASSERT_GT(x_axis.count, 100);
  ASSERT_GT(y_axis.count, 100);
  EXPECT_NEAR(x_axis.x_px, y_axis.x_px, 8.0) << "both run right by cos 30";
  EXPECT_GT(x_axis.y_px, y_axis.y_px + 50) << "x goes down the picture, y up";
}

// One ligament on top of a 10 mm cylinder (u = 0) and one node pass under it (u = pi R).
PreviewScene top_and_bottom() {
  slicer::Toolpath t;
  auto stroke = [](double u, slicer::Feature f) {
    slicer::Stroke s;
    s.start_mm = {u, -8};
    s.segments = {slicer::line_to({u, 8}, f)};
    s.width_mm = 1.0;
    return s;
  };
  t.layers.push_back({0.5, 0.5, {stroke(0, slicer::Feature::Ligament), stroke(M_PI * 10, slicer::Feature::Node)}});
  return strand::testing::cylinder_scene(t, 10.0, 30.0);
}

TEST(PreviewImage, SubstrateHidesTheFarSideOfASleeve) {
  ImageOptions o;
  o.width_px = 500;
  o.height_px = 400;
  o.scale_bar = false;  // no legend swatches in the counts
  for (const auto view : {PreviewView::Top, PreviewView::Iso}) {
    o.view = view;
    PreviewScene scene = top_and_bottom();
    const std::string png = render_png(scene, o);
    EXPECT_GT(pixels_of(png, slicer::Feature::Ligament), 500) << "the top ligament shows";
    EXPECT_EQ(pixels_of(png, slicer::Feature::Node), 0) << "the pass under the cylinder is hidden";
    // the light substrate (greys 204..240, shaded by facing) covers much of the picture
    EXPECT_GT(strand::testing::colour_spot(png, 222, 222, 230, 60).count, 50000);
    scene.substrate = {};  // seen from above the pass lies right under the ligament
    if (view == PreviewView::Iso) {
      EXPECT_GT(pixels_of(render_png(scene, o), slicer::Feature::Node), 500) << "without it, it shows";
    }
  }
}

// A part filled by `strand slice` lies inside its mesh: the mesh is a backdrop, so the pass
// the cylinder would hide as a substrate is drawn, over the still visible solid.
TEST(PreviewImage, APartsMeshDoesNotHideItsFill) {
  ImageOptions o;
  o.width_px = 500;
  o.height_px = 400;
  o.scale_bar = false;
  o.view = PreviewView::Iso;
  PreviewScene scene = top_and_bottom();
  scene.substrate_hides_paths = false;
  const std::string png = render_png(scene, o);
  EXPECT_GT(pixels_of(png, slicer::Feature::Node), 500) << "the pass under the cylinder shows";
  EXPECT_GT(pixels_of(png, slicer::Feature::Ligament), 500);
  EXPECT_GT(strand::testing::colour_spot(png, 222, 222, 230, 60).count, 50000) << "mesh drawn";
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
