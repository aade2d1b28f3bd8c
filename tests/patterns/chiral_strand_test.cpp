// Node hairpins and layer strands of chiral lattices, checked on the exact segments.
#include "patterns/chiral_strand.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "slicer/units.h"

namespace strand::patterns {
namespace {

using slicer::Vec2;

TEST(NodeHairpin, OnePassPerRadiusEndingOnTheAttachCircleAtTheExit) {
  const Vec2 c(3, -2);
  for (int passes : {1, 3, 5}) {
    for (double sweep : {slicer::kPi / 2, -slicer::kPi / 3}) {
      const NodeRings r = node_rings(1.87, 0.5, 0.4, passes);
      const auto segs = node_hairpin(c, r, 0.3, sweep, 0.4);
      std::multiset<long> radii;
      for (const auto& s : segs) {
        if (s.kind == slicer::SegmentKind::Arc)
          radii.insert(std::lround((s.end_mm - c).norm() * 1000));
      }
      std::multiset<long> expected;
      for (double p : r.pass_mm) expected.insert(std::lround(p * 1000));
      EXPECT_EQ(radii, expected) << passes << " passes";
      const Vec2 exit = c + r.attach_mm * Vec2(std::cos(0.3 + sweep), std::sin(0.3 + sweep));
      EXPECT_NEAR((segs.back().end_mm - exit).norm(), 0.0, 1e-12);
      EXPECT_NEAR((segs.front().end_mm - c).norm(), r.pass_mm.back(), 1e-12)
          << "enters the outer pass";
    }
  }
}

TEST(NodeHairpin, InnerPassesReachBackBeyondTheEntry) {
  const Vec2 c(0, 0);
  const NodeRings r = node_rings(2.0, 0.4, 0.32, 3);
  const auto segs = node_hairpin(c, r, 0.0, 1.0, 0.5);  // ccw sector, extend cw by 0.5 rad
  // the middle pass turns at -0.5 rad
  bool found = false;
  for (const auto& s : segs) {
    const double a = std::atan2(s.end_mm.y(), s.end_mm.x());
    if (s.kind == slicer::SegmentKind::Arc && std::abs(a + 0.5) < 1e-9) found = true;
  }
  EXPECT_TRUE(found);
}

TEST(ChiralLayer, OneClosedStrokeAllFourFeatures) {
  const ChiralLattice l = tetrachiral_lattice(2, 4, 10);
  const auto strokes = chiral_layer(l, node_rings(1.87, 0.5, 0.4, 3), {0.5, 0.4, 5.0});
  ASSERT_EQ(strokes.size(), 1u);
  EXPECT_NEAR((strokes[0].start_mm - strokes[0].end_mm()).norm(), 0.0, 1e-9);
  std::set<slicer::Feature> features;
  for (const auto& s : strokes[0].segments) features.insert(s.feature);
  EXPECT_EQ(features, (std::set<slicer::Feature>{slicer::Feature::Ligament, slicer::Feature::Node,
                                                 slicer::Feature::Grip, slicer::Feature::Frame}));
  EXPECT_EQ(strokes[0].segments.front().feature, slicer::Feature::Grip)
      << "starts in the bottom grip";
}

}  // namespace
}  // namespace strand::patterns
