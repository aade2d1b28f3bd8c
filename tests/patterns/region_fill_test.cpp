// Region fills: clipped pattern pieces joined along the boundary into few strands, with no
// crossing, no bead inside a hole, line positions on one grid in every layer, and the
// deposited porosity close to the pattern's own.
#include "patterns/region_fill.h"

#include <gtest/gtest.h>

#include <cmath>

#include "patterns/region_join.h"
#include "slicer/input_error.h"
#include "slicer/units.h"

namespace strand::patterns {
namespace {

using slicer::Ring;
using slicer::Vec2;

Ring circle(double r, int n, bool ccw = true) {
  Ring out;
  for (int i = 0; i < n; ++i)
    out.push_back(r * slicer::unit_vector((ccw ? 1 : -1) * slicer::kTwoPi * i / n));
  return out;
}

Ring rect(double w, double h) {
  return {Vec2(-w / 2, -h / 2), Vec2(w / 2, -h / 2), Vec2(w / 2, h / 2), Vec2(-w / 2, h / 2)};
}

struct Seg {
  Vec2 a, b;
  int stroke;
  std::size_t index;
};

std::vector<Seg> segments_of(const std::vector<slicer::Stroke>& strokes) {
  std::vector<Seg> out;
  for (std::size_t s = 0; s < strokes.size(); ++s) {
    Vec2 at = strokes[s].start_mm;
    for (std::size_t i = 0; i < strokes[s].segments.size(); ++i) {
      const Vec2 to = strokes[s].segments[i].end_mm;
      if ((to - at).norm() > 1e-9) out.push_back({at, to, static_cast<int>(s), out.size()});
      at = to;
    }
  }
  return out;
}

// Proper crossings between any two segments of a layer (joints of one strand excluded).
int crossings(const std::vector<slicer::Stroke>& strokes) {
  const auto segs = segments_of(strokes);
  int n = 0;
  for (std::size_t i = 0; i < segs.size(); ++i) {
    for (std::size_t j = i + 1; j < segs.size(); ++j) {
      if (segs[i].stroke == segs[j].stroke && j == i + 1) continue;
      n += slicer::segment_contact(segs[i].a, segs[i].b, segs[j].a, segs[j].b, 1e-9) ==
           slicer::Contact::Crossing;
    }
  }
  return n;
}

RegionPattern scaffold(double nozzle, double pitch) {
  RegionPattern p;
  p.name = "scaffold";
  p.nozzle_mm = nozzle;
  p.layer_height_mm = 0.88 * nozzle;
  p.pitch_mm = pitch;
  p.angles_deg = {0.0, 90.0};
  p.min_piece_mm = nozzle;
  p.porosity = 1.0 - slicer::bead_area_mm2(nozzle, p.layer_height_mm) / (pitch * p.layer_height_mm);
  return p;
}

TEST(RegionFill, ConvexRegionIsOneSerpentinePerLayer) {
  const slicer::Region region = slicer::region_from_contours({circle(15, 180)});
  for (int layer : {0, 1}) {
    const LayerFill f = fill_layer(region, scaffold(0.84, 2.44), layer, 0, Vec2(15, 15));
    EXPECT_EQ(f.pattern_strands, 1) << layer;
    EXPECT_EQ(crossings(f.strokes), 0);
  }
}

TEST(RegionFill, HoleGetsNoFilamentAndFewStrands) {
  const slicer::Region region =
      slicer::region_from_contours({circle(12, 180), circle(4, 90, false)});
  const LayerFill f = fill_layer(region, scaffold(0.6, 1.6), 0, 1, Vec2(12, 12));
  EXPECT_EQ(crossings(f.strokes), 0);
  EXPECT_LE(f.pattern_strands, 3) << "an annulus: at most three strands";
  for (const auto& seg : segments_of(f.strokes)) {
    for (double t : {0.0, 0.5, 1.0}) {
      const Vec2 p = seg.a + t * (seg.b - seg.a);
      // The hole is a 90-gon on the 4 mm circle: its edges lie 4 cos(pi / 90) from the centre.
      EXPECT_GT(p.norm(), 4.0 * std::cos(slicer::kPi / 90) + 0.3 - 1e-3)
          << "a bead inside the hole (or its half width)";
      EXPECT_LT(p.norm(), 12.0 - 0.3 + 1e-3);
    }
  }
}

TEST(RegionFill, LinesStayOnTheGlobalGridInEveryLayer) {
  const RegionPattern p = scaffold(0.5, 2.0);
  // Two different regions: lines along x (layer 0) sit at y = k * pitch in both.
  for (const Ring& ring : {rect(20, 13), Ring{Vec2(-3, -7.3), Vec2(9, -5), Vec2(4, 8.1)}}) {
    const LayerFill f = fill_layer(slicer::region_from_contours({ring}), p, 0, 0, Vec2(10, 10));
    for (const auto& seg : segments_of(f.strokes)) {
      if (std::abs(seg.a.y() - seg.b.y()) > 1e-9 || (seg.a - seg.b).norm() < 1.0)
        continue;  // joins
      const double k = seg.a.y() / p.pitch_mm;
      EXPECT_NEAR(k, std::round(k), 1e-9);
    }
  }
}

TEST(RegionFill, ConcaveRegionsStayCrossingFreeWithFewStrands) {
  // A U shape and a comb: lines across the arms are cut into several pieces.
  const Ring u{Vec2(-10, -10), Vec2(10, -10), Vec2(10, 10), Vec2(5, 10),
               Vec2(5, -5),    Vec2(-5, -5),  Vec2(-5, 10), Vec2(-10, 10)};
  Ring comb{Vec2(-15, -10), Vec2(12, -10)};  // a base with five teeth standing on it
  for (int i = 4; i >= 0; --i) {
    const double x0 = -15 + 6 * i, x1 = x0 + 3;
    comb.insert(comb.end(), {Vec2(x1, 10), Vec2(x0, 10)});
    if (i > 0) comb.insert(comb.end(), {Vec2(x0, -4), Vec2(x0 - 3, -4)});
  }
  for (const Ring& ring : {u, comb}) {
    for (int layer : {0, 1}) {
      const LayerFill f = fill_layer(slicer::region_from_contours({ring}), scaffold(0.6, 1.5),
                                     layer, 0, Vec2(15, 10));
      EXPECT_EQ(crossings(f.strokes), 0);
      EXPECT_LE(f.pattern_strands, 6) << "one per arm at most, plus one";
      EXPECT_GE(f.pattern_strands, 1);
    }
  }
}

TEST(RegionFill, DepositedPorosityMatchesThePatternOnALargeBox) {
  PartFill part;
  const RegionPattern p = scaffold(0.84, 2.44);
  for (int k = 0; k < 6; ++k) part.layers.push_back(slicer::region_from_contours({rect(60, 60)}));
  part.half_extent_mm = Vec2(30, 30);
  part.volume_mm3 = 60 * 60 * 6 * p.layer_height_mm;
  const slicer::Toolpath t = fill_part(part, p);
  const double deposited = t.derived.at("porosity").get<double>();
  EXPECT_NEAR(deposited, p.porosity, 0.03) << "joins along the boundary add a little";
  EXPECT_LT(deposited, p.porosity) << "joins add material";
  for (const auto& s : t.derived.at("pattern_strands_per_layer")) EXPECT_EQ(s.get<int>(), 1);
}

TEST(RegionFill, NozzleWiderThanAWallFailsNamingWhere) {
  PartFill part;
  part.half_extent_mm = Vec2(5, 10);
  const RegionPattern p = scaffold(0.84, 2.0);
  for (int k = 0; k < 5; ++k) part.layers.push_back(slicer::region_from_contours({rect(0.6, 20)}));
  try {
    fill_part(part, p);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("wider than the part's wall near (0.000, 0.000, 1.478)"),
              std::string::npos)
        << e.what();
  }
}

TEST(RegionFill, ThinRimAtTheTopOfACurvedPartIsNotAWall) {
  PartFill part;  // a wide disk, then a thin ring on top (a torus' last layer)
  part.half_extent_mm = Vec2(12, 12);
  part.layers = {slicer::region_from_contours({circle(12, 180), circle(6, 90, false)}),
                 slicer::region_from_contours({circle(9.3, 180), circle(8.9, 180, false)})};
  part.volume_mm3 = 1000;
  EXPECT_NO_THROW(fill_part(part, scaffold(0.84, 2.0)));
}

}  // namespace
}  // namespace strand::patterns
