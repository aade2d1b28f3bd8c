// Fills: concentric rings stay inside the region, keep their distance from its border and
// never cross; hatch + outline through the layout; the work bound on fine spacings.
#include "postprocess/plot/fill.h"

#include <gtest/gtest.h>

#include <cmath>

#include "machines/profile.h"
#include "postprocess/plot/plot_layout.h"
#include "slicer/input_error.h"
#include "slicer/svg_import.h"
#include "slicer/units.h"

namespace strand::post {
namespace {

using slicer::Polyline;
using slicer::Vec2;

Polyline square(double x0, double y0, double side) {
  return {Vec2(x0, y0), Vec2(x0 + side, y0), Vec2(x0 + side, y0 + side), Vec2(x0, y0 + side), Vec2(x0, y0)};
}

Polyline circle(const Vec2& c, double r, int n) {
  Polyline p;
  for (int i = 0; i <= n; ++i) p.push_back(slicer::on_circle(c, r, slicer::kTwoPi * i / n));
  return p;
}

double distance_to(const Polyline& pl, const Vec2& q) {
  double d = INFINITY;
  for (std::size_t i = 1; i < pl.size(); ++i) d = std::min(d, slicer::point_segment_distance(q, pl[i - 1], pl[i]));
  return d;
}

bool inside_square(const Vec2& p, double x0, double y0, double side) {
  return p.x() > x0 && p.x() < x0 + side && p.y() > y0 && p.y() < y0 + side;
}

TEST(ConcentricFill, RingsOfASquareWithAHoleStayInsideAndNeverCross) {
  const std::vector<Polyline> region = {square(0, 0, 40), square(15, 15, 10)};
  const double spacing = 2.0;
  const auto rings = concentric_fill(region, true, spacing);
  ASSERT_GT(rings.size(), 8u);
  for (const auto& ring : rings) {
    EXPECT_EQ(ring.front(), ring.back());  // closed
    for (const auto& p : ring) {
      EXPECT_TRUE(inside_square(p, 0, 0, 40) && !inside_square(p, 15, 15, 10)) << p.transpose();
      // a ring is at least one spacing from the border (rounded corners only add distance)
      EXPECT_GE(std::min(distance_to(region[0], p), distance_to(region[1], p)), spacing - 1e-3);
    }
  }
  int crossings = 0;
  for (std::size_t a = 0; a < rings.size(); ++a) {
    for (std::size_t b = a + 1; b < rings.size(); ++b) {
      for (std::size_t i = 1; i < rings[a].size(); ++i) {
        for (std::size_t j = 1; j < rings[b].size(); ++j) {
          crossings += slicer::segment_contact(rings[a][i - 1], rings[a][i], rings[b][j - 1], rings[b][j], 1e-6) !=
                       slicer::Contact::None;
        }
      }
    }
  }
  EXPECT_EQ(crossings, 0);
}

TEST(ConcentricFill, RingsOfADiscAreCirclesOneSpacingApart) {
  const auto rings = concentric_fill({circle(Vec2(50, 50), 20.0, 720)}, false, 1.0);
  // radii 19, 18, ..., 1 (radius 0 is empty)
  ASSERT_EQ(rings.size(), 19u);
  for (std::size_t k = 0; k < rings.size(); ++k) {
    for (const auto& p : rings[k]) EXPECT_NEAR((p - Vec2(50, 50)).norm(), 19.0 - k, 0.01);
  }
}

TEST(ConcentricFill, NonZeroRuleFillsAnOverlapOnce) {
  // two overlapping squares wound the same way: one region, so rings follow their union
  const auto rings = concentric_fill({square(0, 0, 20), square(10, 0, 20)}, false, 1.0);
  ASSERT_FALSE(rings.empty());
  double max_x = -INFINITY;
  for (const auto& p : rings.front()) max_x = std::max(max_x, p.x());
  EXPECT_NEAR(max_x, 29.0, 1e-3);
}

TEST(HatchFill, LinesStayInsideTheRegionAndSkipTheHole) {
  const auto lines = hatch_fill({square(0, 0, 40), square(15, 15, 10)}, true, 1.0, 0.0);
  // 40 horizontal lines, the 10 through the hole split in two
  EXPECT_EQ(lines.size(), 50u);
  for (const auto& l : lines) {
    for (const auto& p : l) {
      EXPECT_TRUE(p.x() >= -1e-6 && p.x() <= 40 + 1e-6);
      EXPECT_FALSE(inside_square(p, 15 + 1e-6, 15 + 1e-6, 10 - 2e-6));
    }
  }
}

TEST(Fill, TooFineASpacingIsRefusedBeforeAnyWork) {
  try {
    hatch_fill({square(0, 0, 300)}, false, 1e-4, 45.0);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("plot.hatch-spacing = 1e-04"), std::string::npos) << e.what();
  }
  EXPECT_THROW(concentric_fill({square(0, 0, 300)}, false, 1e-4), InputError);
}

TEST(Fill, FarCoordinatesAreInputErrorsNotClipperExceptions) {
  // Clipper 6 throws past about 4.6e14 mm at this scale: the range is checked first
  for (const double far : {1e15, 1e308, static_cast<double>(INFINITY)}) {
    EXPECT_THROW(hatch_fill({square(0, 0, 10), square(far, 0, 10)}, false, 1.0, 45.0), InputError)
        << far;
    EXPECT_THROW(concentric_fill({square(far, 0, 10)}, false, 1.0), InputError) << far;
  }
}

TEST(Fill, PointBoundCoversWhatTheFillsDraw) {
  const std::vector<Polyline> region = {square(0, 0, 50), circle(Vec2(25, 25), 10, 90)};
  for (const double angle : {0.0, 30.0, 45.0, 90.0}) {
    double points = 0;
    for (const auto& pl : hatch_fill(region, true, 0.7, angle))
      points += static_cast<double>(pl.size());
    const double bound = fill_point_bound(region, FillStyle::Hatch, 0.7, angle);
    EXPECT_GE(bound, points) << angle;
    EXPECT_LE(bound, 4 * points + 1000) << angle;
  }
  double ring_points = 0;
  for (const auto& pl : concentric_fill(region, true, 0.7))
    ring_points += static_cast<double>(pl.size());
  EXPECT_GE(fill_point_bound(region, FillStyle::Concentric, 0.7, 0.0), ring_points);
  EXPECT_EQ(fill_point_bound(region, FillStyle::None, 0.7, 0.0), 0.0);
}

// A filled, unstroked 40 mm square through the layout on an XY plotter.
slicer::SvgDrawing filled_square() {
  return slicer::import_svg(
      "<svg xmlns='http://www.w3.org/2000/svg' width='40mm' height='40mm' viewBox='0 0 40 40'>"
      "<rect width='40' height='40' fill='black'/></svg>",
      "square.svg");
}

std::size_t closed_strokes(const slicer::Toolpath& t) {
  std::size_t n = 0;
  for (const auto& s : t.layers[0].strokes) n += s.segments.size() >= 3 && (s.end_mm() - s.start_mm).norm() < 1e-9;
  return n;
}

TEST(FillLayout, HatchDrawsLinesAndTheOutline) {
  const auto m = machines::load_profile("xy-plotter-servo");
  PlotOptions o;
  o.hatch_spacing_mm = {2.0};
  const auto t = layout_plot(filled_square(), m, o);
  EXPECT_EQ(closed_strokes(t), 1u);  // the outline
  // 45 degree hatch across a 40 mm square, 2 mm apart: diagonal 56.6 mm -> 28 lines
  EXPECT_EQ(t.layers[0].strokes.size(), 28u + 1u);
}

TEST(FillLayout, OutlineOnlyAndNone) {
  const auto m = machines::load_profile("xy-plotter-servo");
  PlotOptions o;
  o.fill = FillStyle::Outline;
  const auto t = layout_plot(filled_square(), m, o);
  ASSERT_EQ(t.layers[0].strokes.size(), 1u);
  EXPECT_NEAR(slicer::stroke_length(t.layers[0].strokes[0]), 160.0, 1e-6);
  o.fill = FillStyle::None;
  EXPECT_THROW(layout_plot(filled_square(), m, o), InputError);
}

TEST(FillLayout, SpacingAndAnglePerPen) {
  EXPECT_EQ(per_pen({}, 3, 0.5), 0.5);
  EXPECT_EQ(per_pen({1.0, 2.0}, 1, 0.5), 1.0);
  EXPECT_EQ(per_pen({1.0, 2.0}, 2, 0.5), 2.0);
  EXPECT_EQ(per_pen({1.0, 2.0}, 4, 0.5), 2.0);
}

}  // namespace
}  // namespace strand::post
