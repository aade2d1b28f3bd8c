// Thin features: a free-standing rib narrower than two beads becomes one centre bead reaching
// its ends, a fin on a block one bead clear of the block's fill, a rib narrower than half a
// bead nothing (left in the fill region for the wall check), a wide part unchanged.
#include "patterns/thin_feature.h"

#include <gtest/gtest.h>

namespace strand::patterns {
namespace {

using slicer::Region;
using slicer::Vec2;

Region box(double x0, double y0, double x1, double y1) {
  return {{{Vec2(x0, y0), Vec2(x1, y0), Vec2(x1, y1), Vec2(x0, y1)}, {}}};
}

std::vector<Vec2> points_of(const slicer::Stroke& s) {
  std::vector<Vec2> out{s.start_mm};
  for (const auto& seg : s.segments) out.push_back(seg.end_mm);
  return out;
}

TEST(ThinFeature, ARibOfOneMillimetreGetsOneCentreBeadAlongItsMiddle) {
  const Region rib = box(0, -0.5, 20, 0.5);
  const ThinFeatures t = thin_features(rib, 0.6, 0.5);
  ASSERT_EQ(t.beads.size(), 1u);
  const auto pts = points_of(t.beads[0]);
  for (const Vec2& p : pts) EXPECT_NEAR(p.y(), 0.0, 0.05) << p.transpose();
  // Stretched until the 0.6 mm bead reaches each end: 0.3 mm short of it.
  EXPECT_NEAR(std::min(pts.front().x(), pts.back().x()), 0.3, 0.05);
  EXPECT_NEAR(std::max(pts.front().x(), pts.back().x()), 19.7, 0.05);
  EXPECT_NEAR(t.length_mm, 19.4, 0.05);
  EXPECT_EQ(t.beads[0].width_mm, 0.6);
  EXPECT_EQ(t.beads[0].height_mm, 0.5);
  EXPECT_TRUE(t.fill_region.empty()) << "the bead alone prints the rib (no folded perimeter)";
}

TEST(ThinFeature, ARibNarrowerThanHalfABeadGetsNoneAndStaysInTheFillRegion) {
  const Region rib = box(0, -0.1, 20, 0.1);
  const ThinFeatures t = thin_features(rib, 0.6, 0.5);
  EXPECT_TRUE(t.beads.empty());
  EXPECT_EQ(t.fill_region, rib);
}

TEST(ThinFeature, AWidePartIsLeftToTheFill) {
  const Region plate = box(0, 0, 20, 10);
  const ThinFeatures t = thin_features(plate, 0.6, 0.5);
  EXPECT_TRUE(t.beads.empty());
  EXPECT_EQ(t.fill_region, plate);
}

TEST(ThinFeature, AFinOnABlockIsOneBeadANozzleClearOfTheBlocksFill) {
  // A 20 mm block with a 0.5 mm fin standing 9 mm out of its side; nozzle 0.84 (the fin is
  // more than half a bead wide and no bead centred 0.42 mm inside reaches it).
  std::vector<slicer::Ring> loops = slicer::rings_of(box(0, 0, 20, 20));
  loops.push_back(slicer::rings_of(box(8, 19, 8.5, 29))[0]);
  const Region part = slicer::region_from_oriented_loops(loops);
  const double d = 0.84;
  const ThinFeatures t = thin_features(part, d, 0.5);
  ASSERT_EQ(t.beads.size(), 1u);
  const auto pts = points_of(t.beads[0]);
  for (const Vec2& p : pts) EXPECT_NEAR(p.x(), 8.25, 0.05) << p.transpose();
  const double lo = std::min(pts.front().y(), pts.back().y());
  const double hi = std::max(pts.front().y(), pts.back().y());
  EXPECT_NEAR(hi, 29.0 - 0.25, 0.05) << "the fin's free end: the bead overreaches it";
  // The block's beads are centred d/2 inside its side (y = 20), bulging 0.08 mm up into the
  // fin's root (a 0.42 mm disc fits that far): the fin's bead starts a nozzle further out.
  EXPECT_GT(lo, 20.0 - d / 2 + d);
  EXPECT_LT(lo, 20.0 - d / 2 + d + 0.1);
  const Region fill_centres = slicer::offset_region(t.fill_region, -d / 2);
  for (const Vec2& p : pts) {
    EXPECT_FALSE(slicer::contains(slicer::offset_region(fill_centres, d - 0.01), p))
        << p.transpose() << " is within a nozzle of the fill";
  }
  EXPECT_NEAR(slicer::area_mm2(t.fill_region), 400.0, 0.5) << "the fin left the fill region";
}

TEST(ThinFeature, ATooNarrowFinBesideAPrintedOneStaysForTheWallCheck) {
  // Fins of 0.5 mm (printed) and 0.3 mm (under half of the 0.84 mm bead) on one block.
  std::vector<slicer::Ring> loops = slicer::rings_of(box(0, 0, 20, 20));
  loops.push_back(slicer::rings_of(box(4, 19, 4.5, 29))[0]);
  loops.push_back(slicer::rings_of(box(14, 19, 14.3, 29))[0]);
  const Region part = slicer::region_from_oriented_loops(loops);
  const ThinFeatures t = thin_features(part, 0.84, 0.5);
  ASSERT_EQ(t.beads.size(), 1u);
  EXPECT_NEAR(t.beads[0].start_mm.x(), 4.25, 0.05);
  EXPECT_NEAR(slicer::area_mm2(t.fill_region), 400.0 + 0.3 * 9.0, 0.5)
      << "the narrow fin stays in the fill region";
}

TEST(ThinFeature, SameLayerSameBeads) {
  std::vector<slicer::Ring> loops = slicer::rings_of(box(0, 0, 20, 20));
  loops.push_back(slicer::rings_of(box(8, 19, 8.5, 29))[0]);
  const Region part = slicer::region_from_oriented_loops(loops);
  const ThinFeatures a = thin_features(part, 0.84, 0.5), b = thin_features(part, 0.84, 0.5);
  EXPECT_EQ(a.beads, b.beads);
  EXPECT_EQ(a.fill_region, b.fill_region);
}

}  // namespace
}  // namespace strand::patterns
