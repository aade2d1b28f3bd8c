// Strands joined straight across a neck: two ends a bead or two apart on either side of a
// neck become one strand where the link keeps half a bead clear of every other bead and of the
// part's edge, and stay apart where it would not.
#include "patterns/neck_links.h"

#include <gtest/gtest.h>

#include "patterns/region_fill.h"
#include "patterns/region_strands.h"
#include "patterns/registry.h"
#include "tests/support/stroke_crossings.h"

namespace strand::patterns {
namespace {

using slicer::Stroke;
using slicer::Vec2;

constexpr double kNozzle = 0.6;
const NeckLinkOptions kOptions{3.0 * kNozzle, 0.5 * kNozzle, 0.25 * kNozzle};

slicer::Ring box(double x0, double y0, double x1, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

// Two 8 x 6 mm blocks joined by a neck `neck_mm` wide and 1.2 mm long on the x axis.
slicer::Region eight(double neck_mm) {
  const double h = neck_mm / 2.0;
  return slicer::region_from_oriented_loops(
      {box(-8.6, -3, -0.5, 3), box(-0.7, -h, 0.7, h), box(0.5, -3, 8.6, 3)});
}

Stroke line(Vec2 a, Vec2 b) { return {a, {slicer::line_to(b, slicer::Feature::Infill)}}; }

std::size_t crossings(const std::vector<slicer::Stroke>& strokes) {
  return testing::layer_crossings(strokes);
}

TEST(NeckLinks, EndsEitherSideOfANeckAreJoined) {
  const std::vector<Stroke> strands{line({-6, 0}, {-0.8, 0}), line({6, 0}, {0.8, 0})};
  const std::vector<Stroke> out = link_across_necks(strands, {}, eight(1.2), kOptions);
  ASSERT_EQ(out.size(), 1u);
  // From one far end through the neck to the other: 5.2 + 1.6 + 5.2 mm.
  EXPECT_NEAR(slicer::stroke_length(out[0]), 12.0, 1e-9);
  EXPECT_EQ(
      (out[0].start_mm - Vec2(-6, 0)).norm() < 1e-9 || (out[0].start_mm - Vec2(6, 0)).norm() < 1e-9,
      true);
}

TEST(NeckLinks, ALinkIsRefusedNearABeadTheEdgeOrOutsideThePart) {
  const std::vector<Stroke> strands{line({-6, 0}, {-0.8, 0}), line({6, 0}, {0.8, 0})};
  // A perimeter bead 0.2 mm from the link's way (closer than half a bead).
  const std::vector<Stroke> near{line({-0.4, 0.2}, {0.4, 0.2})};
  EXPECT_EQ(link_across_necks(strands, near, eight(1.2), kOptions).size(), 2u);
  // A neck 0.25 mm wide leaves the link 0.125 mm from the part's edge.
  EXPECT_EQ(link_across_necks(strands, {}, eight(0.25), kOptions).size(), 2u);
  // No neck at all: the way between the blocks lies outside the part.
  const slicer::Region apart =
      slicer::region_from_oriented_loops({box(-8.6, -3, -0.5, 3), box(0.5, -3, 8.6, 3)});
  EXPECT_EQ(link_across_necks(strands, {}, apart, kOptions).size(), 2u);
  // Ends further apart than the reach.
  const std::vector<Stroke> far{line({-6, 0}, {-1.0, 0}), line({6, 0}, {1.0, 0})};
  EXPECT_EQ(link_across_necks(far, {}, eight(1.2), kOptions).size(), 2u);
}

// Three strands in a row: both links taken, one chain, and never a chain closed on itself.
TEST(NeckLinks, ChainsRunThroughSeveralLinksAndNeverClose) {
  const slicer::Region wide = slicer::region_from_contours({box(-10, -5, 10, 5)});
  const std::vector<Stroke> strands{line({-8, 0}, {-0.8, 0}), line({0.8, 0}, {0.8, 3}),
                                    line({-0.8, 3}, {-8, 3})};
  const std::vector<Stroke> out = link_across_necks(strands, {}, wide, kOptions);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NEAR(slicer::stroke_length(out[0]), 7.2 + 1.6 + 3 + 1.6 + 7.2, 1e-9);
  // The chain's two free ends: the far ends of the first and the last strand, not linked.
  EXPECT_NEAR((out[0].start_mm - out[0].end_mm()).norm(), 3.0, 1e-9);
}

// A layer of an eight with one perimeter: the fill, a bead and a half in, splits at the neck
// (2.3 beads wide); the perimeter loop runs through it, and the one chord of each block, on the
// neck's axis, ends beside it. One strand, no crossing.
TEST(NeckLinks, AnEightWithAPerimeterIsOneStrand) {
  const slicer::Region region = slicer::region_from_oriented_loops(
      {box(-8.6, -1.9, -0.2, 1.9), box(-0.4, -0.7, 0.4, 0.7), box(0.2, -1.9, 8.6, 1.9)});
  const RegionPattern p =
      region_pattern(*find_generator("scaffold"), {{"nozzle", kNozzle}, {"gap", 1.0}}, {10, 4});
  const LayerFill f = fill_layer(region, p, 0, 1, {10, 4});
  EXPECT_EQ(strands_over_bound(strands_per_region(bead_parts(region, kNozzle), f.strokes)), 0);
  EXPECT_EQ(f.strokes.size(), 1u);
  EXPECT_EQ(crossings(f.strokes), 0u);
}

double deposited(const std::vector<Stroke>& strokes) {
  double len = 0.0;
  for (const Stroke& s : strokes) len += slicer::stroke_length(s);
  return len;
}

// A fin about a bead wide: its perimeter, half a bead in, is a ring with its two sides almost
// on top of each other. It is printed once, as one open line, not as a bead there and back.
TEST(NeckLinks, AFlatPerimeterIsPrintedOnce) {
  const slicer::Region fin = slicer::region_from_contours({box(0, 0, 10, 0.62)});
  const RegionPattern p =
      region_pattern(*find_generator("scaffold"), {{"nozzle", kNozzle}, {"gap", 1.0}}, {10, 4});
  const LayerFill f = fill_layer(fin, p, 0, 1, {10, 4});
  ASSERT_EQ(f.strokes.size(), 1u);
  EXPECT_NEAR(deposited(f.strokes), 10 - kNozzle, 0.05);  // there and back would be twice
  EXPECT_GT((f.strokes[0].end_mm() - f.strokes[0].start_mm).norm(), 9.0);
}

// The same fin with two notches under a bead wide: its flat perimeter breaks in three, and
// on a layer over the bound the three are linked through the notches (a quarter bead inside
// the edge at least) into one strand.
TEST(NeckLinks, APerimeterBrokenAtNotchesIsLinkedAgain) {
  const slicer::Region fin = slicer::region_from_oriented_loops(
      {box(0, 0, 3, 0.64), box(2.9, 0.07, 4.1, 0.57), box(4, 0, 6, 0.64), box(5.9, 0.07, 7.1, 0.57),
       box(7, 0, 10, 0.64)});
  const RegionPattern p =
      region_pattern(*find_generator("scaffold"), {{"nozzle", kNozzle}, {"gap", 1.0}}, {10, 4});
  const LayerFill f = fill_layer(fin, p, 0, 1, {10, 4});
  EXPECT_EQ(f.strokes.size(), 1u);
  EXPECT_NEAR(deposited(f.strokes), 10 - kNozzle, 0.1);
  EXPECT_EQ(crossings(f.strokes), 0u);
}

// The bound counts parts as a bead sees them: blocks joined by a neck narrower than half a bead
// (no bead prints it) are two parts, and a hole whose wall is that thin is no hole.
TEST(NeckLinks, TheBoundCountsPartsAsABeadSeesThem) {
  EXPECT_EQ(bead_parts(eight(0.25), kNozzle).size(), 2u);
  EXPECT_EQ(bead_parts(eight(0.35), kNozzle).size(), 1u);
  const slicer::Region ring =
      slicer::region_from_contours({box(-5, -5, 5, 5), box(-4.9, -4, 4, 4)});
  ASSERT_EQ(ring.size(), 1u);
  ASSERT_EQ(ring[0].holes.size(), 1u);
  const slicer::Region seen = bead_parts(ring, kNozzle);
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_EQ(seen[0].holes.size(), 0u);
  // Two strands in what a bead sees as two parts are within the bound.
  const std::vector<Stroke> two{line({-6, 0}, {-2, 0}), line({6, 0}, {2, 0})};
  EXPECT_EQ(strands_over_bound(strands_per_region(eight(0.25), two)), 1);
  EXPECT_EQ(strands_over_bound(strands_per_region(bead_parts(eight(0.25), kNozzle), two)), 0);
}

}  // namespace
}  // namespace strand::patterns
