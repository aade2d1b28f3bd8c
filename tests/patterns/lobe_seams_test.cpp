// Seams down a scaffold layer's dead-end lobes: a body with legs below it (and above it)
// fills as one crossing-free strand, each leg down one half and back up the other, where
// whole chords joined along the boundary leave one strand per leg but one.
#include "patterns/lobe_seams.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "patterns/region_fill.h"
#include "patterns/region_strands.h"
#include "patterns/registry.h"
#include "tests/support/stroke_crossings.h"

namespace strand::patterns {
namespace {

using slicer::Vec2;

slicer::Ring box(double x0, double y0, double x1, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

// A body 20 mm wide, 8 mm tall, with `legs` legs `leg_mm` wide and 10 mm long at its two
// sides, below it (and above it when `both`): the union as one region.
slicer::Region legged(double leg_mm, bool both) {
  std::vector<slicer::Ring> loops{box(-10, 0, 10, 8), box(-10, -10, -10 + leg_mm, 0.5),
                                  box(10 - leg_mm, -10, 10, 0.5)};
  if (both) {
    loops.push_back(box(-10, 7.5, -10 + leg_mm, 18));
    loops.push_back(box(10 - leg_mm, 7.5, 10, 18));
  }
  return slicer::region_from_oriented_loops(loops);
}

RegionPattern scaffold(const Vec2& half) {
  return region_pattern(*find_generator("scaffold"), {{"nozzle", 0.6}, {"gap", 1.0}}, half);
}

std::size_t crossings(const std::vector<slicer::Stroke>& strokes) {
  return testing::layer_crossings(strokes);
}

// Deposited length inside the box (segment midpoints), mm.
double length_in(const std::vector<slicer::Stroke>& strokes, const slicer::Ring& where) {
  const slicer::Region r = slicer::region_from_contours({where});
  double len = 0.0;
  for (const slicer::Stroke& s : strokes) {
    Vec2 at = s.start_mm;
    for (const auto& seg : s.segments) {
      if (slicer::contains(r, (at + seg.end_mm) / 2.0)) len += (seg.end_mm - at).norm();
      at = seg.end_mm;
    }
  }
  return len;
}

// Layer 0's lines run along x, across the legs: each leg is a dead end.
TEST(LobeSeams, ABodyOnTwoLegsIsOneStrandDownAndBackUpALeg) {
  for (const double leg : {6.0, 3.0}) {
    const slicer::Region region = legged(leg, false);
    const RegionPattern p = scaffold({12, 20});
    const LayerFill f = fill_layer(region, p, 0, 0, {12, 20});
    EXPECT_EQ(f.strokes.size(), 1u) << "legs " << leg << " mm";
    EXPECT_EQ(crossings(f.strokes), 0u);
    // Both legs filled: about a line per pitch across each, there and back in one of them.
    const double rows = 9.0 / p.pitch_mm;
    for (const double x0 : {-10.0, 10.0 - leg}) {
      EXPECT_GT(length_in(f.strokes, box(x0, -10, x0 + leg, -1)), 0.6 * rows * (leg - 0.6))
          << "legs " << leg << " mm, the leg at x " << x0;
    }
  }
}

// The bound is a part's: a sliver too thin for any chord beside the body (a second part, with
// no strand) must not let the body keep a strand too many, as the layer's totals (2 strands,
// 2 parts) would.
TEST(LobeSeams, ABodyBesideASliverStillGetsItsSeam) {
  slicer::Region region = legged(6.0, false);
  for (auto& part : slicer::region_from_contours({box(14, 0, 14.3, 8)}))
    region.push_back(std::move(part));
  ASSERT_EQ(region.size(), 2u);
  const LayerFill f = fill_layer(region, scaffold({16, 20}), 0, 0, {16, 20});
  EXPECT_EQ(f.strokes.size(), 1u);
  EXPECT_EQ(strands_over_bound(strands_per_region(region, f.strokes)), 0);
  EXPECT_EQ(crossings(f.strokes), 0u);
}

TEST(LobeSeams, AnHIsOneStrand) {
  const slicer::Region region = legged(5.0, true);
  const LayerFill f = fill_layer(region, scaffold({12, 20}), 0, 0, {12, 20});
  EXPECT_EQ(f.strokes.size(), 1u);
  EXPECT_EQ(crossings(f.strokes), 0u);
}

// An H whose legs taper from 2.6 mm to 1.4 mm: chords down a leg are long enough to halve
// near the body and too short near the tip, where a leg's chords can only be left out. Every
// leg is still filled, there and back in all but two, as one crossing-free strand.
TEST(LobeSeams, AnHOnTaperingLegsIsOneStrand) {
  std::vector<slicer::Ring> loops{box(-10, 0, 10, 5)};
  for (const double side : {-1.0, 1.0}) {
    for (const double up : {-1.0, 1.0}) {
      const double x = side * 10.0, y0 = up < 0 ? 0.5 : 4.5, y1 = up < 0 ? -10.0 : 15.0;
      const double in = x - side * 2.6, tip = x - side * 1.4;
      loops.push_back(side < 0 ? slicer::Ring{{x, y0}, {in, y0}, {tip, y1}, {x, y1}}
                               : slicer::Ring{{in, y0}, {x, y0}, {x, y1}, {tip, y1}});
    }
  }
  for (auto& ring : loops) {
    if (slicer::signed_area_mm2(ring) < 0) std::reverse(ring.begin(), ring.end());
  }
  const slicer::Region region = slicer::region_from_oriented_loops(loops);
  ASSERT_EQ(region.size(), 1u);
  const LayerFill f = fill_layer(region, scaffold({12, 20}), 0, 0, {12, 20});
  EXPECT_EQ(f.strokes.size(), 1u);
  EXPECT_EQ(crossings(f.strokes), 0u);
  for (const double x0 : {-10.0, 8.6}) {
    for (const double y0 : {-9.0, 6.0}) {
      EXPECT_GT(length_in(f.strokes, box(x0, y0, x0 + 1.4, y0 + 8.0)), 8.0)
          << "the leg at " << x0 << ", " << y0;
    }
  }
}

// Legs narrower than a pitch (their chords too short to halve): their chords are left out
// instead, and each leg is printed round its edge, out along one side and back the other.
TEST(LobeSeams, LegsNarrowerThanAPitchAreFilledRoundTheirEdge) {
  const double leg = 1.8;  // 1.2 mm of fill: a chord of 1.2 mm, shorter than the 1.6 mm pitch
  const std::vector<double> at{-8.0, -3.0, 2.0, 6.5};
  std::vector<slicer::Ring> loops{box(-10, 0, 10, 8)};
  for (const double x0 : at) loops.push_back(box(x0, -10, x0 + leg, 0.5));
  const slicer::Region region = slicer::region_from_oriented_loops(loops);
  const slicer::Region fill = slicer::offset_region(region, -0.3);
  const RegionPattern p = scaffold({12, 20});
  const RingSet rs = ring_set(slicer::rings_of(fill));
  std::vector<FillPiece> pieces = clip_to_rings(rs, pattern_lines(p, 0, {12, 20}));
  const LobeSeams seams = lobe_seams(fill, pieces, {0.6, p.pitch_mm, 0.3});
  int dropped = 0;
  for (std::size_t c = 0; c < seams.dead_ends; ++c) {
    if (!seams.cells[c].front().drop) continue;
    ++dropped;
    // One piece round the leg replaces its chords: along both sides and the tip.
    const std::size_t before = pieces.size();
    ASSERT_TRUE(round_lobe(rs, seams.cells[c].front().region, pieces));
    EXPECT_LT(pieces.size(), before);
  }
  EXPECT_EQ(dropped, 4);
  const LayerFill f = fill_layer(region, p, 0, 0, {12, 20});
  EXPECT_EQ(f.strokes.size(), 1u);
  EXPECT_EQ(crossings(f.strokes), 0u);
  // Every leg filled: round its edge (9 mm of it in the box, down and back up), or with its
  // chords where the strand starts or ends.
  int round = 0;
  for (const double x0 : at) {
    const double len = length_in(f.strokes, box(x0, -10, x0 + leg, -1));
    EXPECT_GT(len, 0.6 * 9.0 / p.pitch_mm * (leg - 0.6)) << "the leg at x " << x0;
    round += len > 2 * 8.0 ? 1 : 0;
  }
  EXPECT_GE(round, 2);
}

// A body on three legs, the middle one forking into two toes: a strand from one outer leg to
// the other must go down the middle leg and back up it, so that leg is cut as well as its
// toes, though it is no dead end (the cells off the path between two dead ends: a spine).
TEST(LobeSeams, ABranchOffTheWayIsCutWhereverItForks) {
  const slicer::Region region = slicer::region_from_oriented_loops(
      {box(-10, 0, 10, 8), box(-10, -10, -6, 0.5), box(6, -10, 10, 0.5), box(-3, -5, 3, 0.5),
       box(-3, -12, -0.8, -4.5), box(0.8, -12, 3, -4.5)});
  ASSERT_EQ(region.size(), 1u);
  const RegionPattern p = scaffold({12, 20});
  const slicer::Region fill = slicer::offset_region(region, -0.3);
  const RingSet rs = ring_set(slicer::rings_of(fill));
  const LobeSeams seams =
      lobe_seams(fill, clip_to_rings(rs, pattern_lines(p, 0, {12, 20})), {0.6, p.pitch_mm, 0.3});
  // Some spine leaves a cell that is no dead end off its path.
  bool inner_off = false;
  for (const auto& off : seams.spines) {
    inner_off = inner_off || std::any_of(off.begin(), off.end(),
                                         [&](std::size_t c) { return c >= seams.dead_ends; });
  }
  EXPECT_TRUE(inner_off);
  const LayerFill f = fill_layer(region, p, 0, 0, {12, 20});
  EXPECT_EQ(f.strokes.size(), 1u);
  EXPECT_EQ(crossings(f.strokes), 0u);
  for (const auto& [x0, x1] :
       {std::pair{-10.0, -6.0}, std::pair{6.0, 10.0}, std::pair{-3.0, -0.8}, std::pair{0.8, 3.0}}) {
    EXPECT_GT(length_in(f.strokes, box(x0, -10, x1, -6)), 0.6 * 4.0 / p.pitch_mm * (x1 - x0 - 0.6))
        << "the leg or toe at x " << x0;
  }
}

// The slits: the cells at a dead end come first (the legs, and the body, whose top row
// has nothing above), each slit inside the fill region away from its boundary, a leg's
// cutting every chord of the leg.
TEST(LobeSeams, SlitsLieInsideTheLegsAndCutEveryChord) {
  const slicer::Region fill = slicer::offset_region(legged(6.0, false), -0.3);
  const RegionPattern p = scaffold({12, 20});
  const RingSet rs = ring_set(slicer::rings_of(fill));
  std::vector<FillPiece> pieces = clip_to_rings(rs, pattern_lines(p, 0, {12, 20}));
  const LobeSeams seams = lobe_seams(fill, pieces, {0.6, p.pitch_mm, 0.3});
  ASSERT_EQ(seams.dead_ends, 3u);
  ASSERT_EQ(seams.cells.size(), 3u);
  int legs = 0;
  for (std::size_t c = 0; c < seams.dead_ends; ++c) {
    ASSERT_FALSE(seams.cells[c][0].drop);
    const slicer::Region& slit = seams.cells[c][0].region;
    ASSERT_EQ(slit.size(), 1u);
    EXPECT_TRUE(slicer::region_difference(slit, slicer::offset_region(fill, -0.05)).empty());
    const auto [lo, hi] = slicer::region_bounds(slit);
    EXPECT_LT(hi.x() - lo.x(), 1.5);
    if (lo.y() > 0.0) continue;  // the body's
    ++legs;
    EXPECT_GT(lo.y(), -10.0) << "slit " << c << " stays inside its leg's tip";
    EXPECT_LT(hi.y(), 1.6) << "slit " << c << " stops short of the body's first whole chord";
    // Every chord of the leg crosses the slit.
    for (const FillPiece& piece : pieces) {
      const Vec2 a = piece.line.points.front(), b = piece.line.points.back();
      const double y = a.y();
      if (y > -0.5 || std::max(a.x(), b.x()) < lo.x() || std::min(a.x(), b.x()) > hi.x()) continue;
      if (y < lo.y() || y > hi.y()) ADD_FAILURE() << "the chord at y " << y << " is not cut";
    }
  }
  EXPECT_EQ(legs, 2);
  // Chords along the legs (layer 1) have no dead end but the body's: no seam helps there.
  const std::vector<FillPiece> across = clip_to_rings(rs, pattern_lines(p, 1, {12, 20}));
  for (const auto& cell : lobe_seams(fill, across, {0.6, p.pitch_mm, 0.3}).cells)
    EXPECT_FALSE(cell.empty());
}

}  // namespace
}  // namespace strand::patterns
