// Tracing: a disc and a ring rendered by cairo (anti-aliased, as a photo would be) trace to
// circles within one pixel; levels split a gradient into nested layers in order; Otsu;
// image decoding of PNG and netpbm files, damaged and oversized images refused.
#include "slicer/trace.h"

#include <cairo.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

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
    if (k > 0) {
      EXPECT_LT(right_edge(t.levels[k]), right_edge(t.levels[k - 1]));
    }
  }
}

// A page lit unevenly (paper from grey 250 at the top left to 90 at the bottom right) with
// six letters 70 greys darker than the paper around them: I bars and O rings. On the right
// the paper is darker than the letters on the left, so no single threshold finds them all.
GreyImage uneven_page() {
  GreyImage g;
  g.width = 240;
  g.height = 120;
  g.grey.resize(240 * 120);
  for (int y = 0; y < g.height; ++y) {
    for (int x = 0; x < g.width; ++x) {
      const double paper = 250 - 120.0 * x / 239 - 40.0 * y / 119;
      bool ink = false;
      for (int k = 0; k < 6; ++k) {
        const double dx = x + 0.5 - (20 + 40 * k), dy = y + 0.5 - 60;
        ink |= k % 2 == 0 ? std::abs(dx) <= 2.5 && std::abs(dy) <= 15
                          : std::hypot(dx, dy) >= 8 && std::hypot(dx, dy) <= 12;
      }
      g.grey[static_cast<std::size_t>(y) * g.width + x] =
          static_cast<std::uint8_t>(std::lround(paper - (ink ? 70 : 0)));
    }
  }
  return g;
}

// Each outline's bounding-box centre and size, in pixels (pixel_mm = 1).
struct Box {
  Vec2 centre, size;
};
std::vector<Box> boxes(const Trace& t) {
  std::vector<Box> out;
  for (const auto& level : t.levels) {
    for (const auto& p : level.paths) {
      Vec2 lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
      for (const auto& q : flatten(p, 0.01)) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
      out.push_back({(lo + hi) / 2, hi - lo});
    }
  }
  return out;
}

// Every outline belongs to a letter: one per I (6 x 30 px), two per O (24 px and its 16 px
// counter), centred on the letter within 0.75 px, its size within 1.5 px (the edge grey
// falls on either side of the threshold).
void expect_letters(const Trace& t) {
  const std::vector<Box> b = boxes(t);
  ASSERT_EQ(b.size(), 9u);
  for (int k = 0; k < 6; ++k) {
    const Vec2 centre(20 + 40 * k, 60);
    std::vector<Box> mine;
    for (const auto& box : b) {
      if ((box.centre - centre).norm() < 0.75) mine.push_back(box);
    }
    ASSERT_EQ(mine.size(), k % 2 == 0 ? 1u : 2u) << "letter " << k;
    if (k % 2 == 0) {
      EXPECT_NEAR(mine[0].size.x(), 6, 1.5);
      EXPECT_NEAR(mine[0].size.y(), 30, 1.5);
    } else {
      const double big = std::max(mine[0].size.x(), mine[1].size.x());
      const double small = std::min(mine[0].size.x(), mine[1].size.x());
      EXPECT_NEAR(big, 24, 1.5);
      EXPECT_NEAR(small, 16, 1.5);
    }
  }
}

TEST(Trace, HighPassFilterTracesAnUnevenlyLitPageToItsLetters) {
  const GreyImage page = uneven_page();
  TraceOptions o;
  o.pixel_mm = 1.0;
  // one global threshold (Otsu's) merges the dark right half of the page into one region
  const std::vector<Box> global = boxes(trace_image(page, o));
  EXPECT_TRUE(
      std::any_of(global.begin(), global.end(), [](const Box& b) { return b.size.x() > 60; }));
  o.highpass_px = 8;
  o.upscale = 2;
  expect_letters(trace_image(page, o));
  o.blur_px = 1;
  expect_letters(trace_image(page, o));
}

TEST(Trace, AdaptiveThresholdTracesAnUnevenlyLitPageToItsLetters) {
  TraceOptions o;
  o.pixel_mm = 1.0;
  o.adaptive = true;
  expect_letters(trace_image(uneven_page(), o));
}

TEST(Trace, FiltersKeepAFlatPageFlatAndScaleBySampling) {
  GreyImage g;
  g.width = 4;
  g.height = 2;
  g.grey = {200, 200, 200, 200, 200, 200, 200, 200};
  TraceOptions o;
  o.highpass_px = 3;
  const GreyImage h = filter_image(g, o);
  EXPECT_EQ(h.grey, std::vector<std::uint8_t>(8, 128));  // paper at mid grey
  o = TraceOptions{};
  g.grey = {0, 100, 100, 100, 0, 100, 100, 100};
  o.upscale = 2;
  const GreyImage u = filter_image(g, o);
  ASSERT_EQ(u.width, 8);
  ASSERT_EQ(u.height, 4);
  // bilinear between pixel centres: 0, 25, 75, 100, ...
  EXPECT_EQ(std::vector<std::uint8_t>(u.grey.begin(), u.grey.begin() + 8),
            (std::vector<std::uint8_t>{0, 25, 75, 100, 100, 100, 100, 100}));
  o.upscale = 9;
  EXPECT_THROW(trace_image(g, o), InputError);
  o.upscale = 8;
  GreyImage huge;
  huge.width = 4096;
  huge.height = 4096;
  huge.grey.assign(4096u * 4096u, 255);
  EXPECT_THROW(trace_image(huge, o), InputError);  // 1 Gpx after upscaling
  o.upscale = 1;
  o.adaptive = true;
  o.levels = 2;
  EXPECT_THROW(trace_image(g, o), InputError);
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
