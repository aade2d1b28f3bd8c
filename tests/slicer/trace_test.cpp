// Tracing: a disc and a ring rendered by cairo (anti-aliased, as a photo would be) trace to
// circles within one pixel; levels split a gradient into nested layers in order; Otsu;
// image decoding of PNG and netpbm files, damaged and oversized images refused.
#include "slicer/trace.h"

#include <cairo.h>
#include <gtest/gtest.h>

#include <cmath>

#include "slicer/image.h"
#include "slicer/input_error.h"

namespace strand::slicer {
namespace {

cairo_status_t append(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

// A white w x h PNG with black circles of the given radii around (cx, cy), filled even-odd
// (two radii: a ring).
std::string circles_png(int w, int h, double cx, double cy, std::vector<double> radii) {
  cairo_surface_t* s = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h);
  cairo_t* cr = cairo_create(s);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_fill_rule(cr, CAIRO_FILL_RULE_EVEN_ODD);
  for (double r : radii) {
    cairo_new_sub_path(cr);
    cairo_arc(cr, cx, cy, r, 0, 2 * M_PI);
  }
  cairo_fill(cr);
  std::string png;
  cairo_surface_write_to_png_stream(s, append, &png);
  cairo_destroy(cr);
  cairo_surface_destroy(s);
  return png;
}

// Distance of every traced point from the centre, in pixels (pixel_mm = 1).
std::vector<double> radii_of(const SubPath& p, const Vec2& c) {
  std::vector<double> out;
  for (const auto& q : flatten(p, 0.01)) out.push_back((q - c).norm());
  return out;
}

TEST(Trace, RenderedDiscTracesToACircleWithinOnePixel) {
  const GreyImage img = decode_image(circles_png(120, 100, 55.3, 48.7, {30.0}), "disc.png");
  TraceOptions o;
  o.pixel_mm = 1.0;
  const Trace t = trace_image(img, o);
  ASSERT_EQ(t.levels.size(), 1u);
  ASSERT_EQ(t.levels[0].paths.size(), 1u);
  for (double r : radii_of(t.levels[0].paths[0], Vec2(55.3, 48.7))) EXPECT_NEAR(r, 30.0, 1.0);
}

TEST(Trace, RenderedRingTracesToTwoCirclesWithinOnePixel) {
  const GreyImage img = decode_image(circles_png(100, 100, 50, 50, {40.0, 25.0}), "ring.png");
  TraceOptions o;
  o.pixel_mm = 1.0;
  const Trace t = trace_image(img, o);
  ASSERT_EQ(t.levels[0].paths.size(), 2u);
  std::vector<double> want = {40.0, 25.0};
  for (std::size_t i = 0; i < 2; ++i) {
    const auto r = radii_of(t.levels[0].paths[i], Vec2(50, 50));
    // potrace lists the outline first, then the hole inside it
    for (double v : r) EXPECT_NEAR(v, want[i], 1.0);
  }
}

TEST(Trace, PixelSizeScalesTheOutline) {
  const GreyImage img = decode_image(circles_png(80, 80, 40, 40, {20.0}), "disc.png");
  TraceOptions o;
  o.pixel_mm = 0.5;
  const Trace t = trace_image(img, o);
  EXPECT_EQ(t.size_mm, Vec2(40, 40));
  for (double r : radii_of(t.levels[0].paths[0], Vec2(20, 20))) EXPECT_NEAR(r, 10.0, 0.5);
}

// A left-to-right gradient from black to white, 256 px wide.
GreyImage gradient() {
  GreyImage g;
  g.width = 256;
  g.height = 40;
  for (int y = 0; y < g.height; ++y) {
    for (int x = 0; x < g.width; ++x) g.grey.push_back(static_cast<std::uint8_t>(x));
  }
  return g;
}

double right_edge(const TraceLevel& l) {
  double x = -INFINITY;
  for (const auto& p : l.paths) {
    for (const auto& q : flatten(p, 0.01)) x = std::max(x, q.x());
  }
  return x;
}

TEST(Trace, LevelsSplitAGradientIntoNestedLayersInOrder) {
  TraceOptions o;
  o.levels = 4;
  o.threshold = 0.8;
  o.pixel_mm = 1.0;
  const Trace t = trace_image(gradient(), o);
  ASSERT_EQ(t.levels.size(), 4u);
  for (int k = 0; k < 4; ++k) {
    // level k+1 holds pixels darker than 0.8 * (4 - k) / 4: x < 255 * that
    const double want = 0.8 * (4 - k) / 4 * 255;
    EXPECT_NEAR(t.levels[k].threshold, 0.8 * (4 - k) / 4, 1e-12);
    ASSERT_EQ(t.levels[k].paths.size(), 1u) << k;
    EXPECT_NEAR(right_edge(t.levels[k]), want, 1.0) << k;
    if (k > 0) EXPECT_LT(right_edge(t.levels[k]), right_edge(t.levels[k - 1]));
  }
}

TEST(Trace, OtsuSplitsTwoGreysInTheMiddle) {
  GreyImage g;
  g.width = 10;
  g.height = 1;
  g.grey = {40, 40, 40, 40, 200, 200, 200, 200, 200, 200};
  const double t = otsu_threshold(g);
  EXPECT_GT(t * 255, 40);
  EXPECT_LE(t * 255, 200);
  EXPECT_NEAR(t * 255, 120, 2);
}

TEST(Image, NetpbmFilesDecode) {
  const GreyImage pbm = decode_image("P1\n3 2\n1 0 1\n0 1 0\n", "a.pbm");
  EXPECT_EQ(pbm.grey, (std::vector<std::uint8_t>{0, 255, 0, 255, 0, 255}));
  const GreyImage pgm = decode_image(std::string("P5 2 1 255\n") + char(10) + char(250), "a.pgm");
  EXPECT_EQ(pgm.grey, (std::vector<std::uint8_t>{10, 250}));
  const GreyImage ppm = decode_image("P3 1 1 255\n255 0 0\n", "a.ppm");
  EXPECT_EQ(ppm.grey, (std::vector<std::uint8_t>{76}));  // Rec. 601 luma of red
}

TEST(Image, DamagedUnknownAndHugeImagesAreRefused) {
  EXPECT_THROW(decode_image("P1\n3 2\n1 0", "short.pbm"), InputError);
  EXPECT_THROW(decode_image("hello, not an image", "x.png"), InputError);
  std::string png = circles_png(10, 10, 5, 5, {3});
  EXPECT_THROW(decode_image(png.substr(0, png.size() / 2), "cut.png"), InputError);
  try {
    decode_image("P5 100000 100000 255\n", "huge.pgm");  // 10 Gpx: refused from the header
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("at most"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace strand::slicer
