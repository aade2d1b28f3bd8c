// Perimeter loops join the strand that ends beside them, never through another bead.
#include "patterns/perimeter_splice.h"

#include <gtest/gtest.h>

namespace strand::patterns {
namespace {

using slicer::Stroke;
using slicer::Vec2;

Stroke square_loop(double half) {
  Stroke s;
  s.start_mm = Vec2(-half, -half);
  for (const Vec2& p : {Vec2(half, -half), Vec2(half, half), Vec2(-half, half), Vec2(-half, -half)}) {
    s.segments.push_back(slicer::line_to(p, slicer::Feature::Wall));
  }
  return s;
}

// A strand from just inside the loop's left side across to its right side.
Stroke strand_across(double half, double gap) {
  Stroke s;
  s.start_mm = Vec2(-half + gap, 0);
  s.segments.push_back(slicer::line_to(Vec2(half - gap, 0), slicer::Feature::Infill));
  return s;
}

TEST(PerimeterSplice, LoopJoinsTheStrandThatEndsBesideIt) {
  const auto out = splice_loops({square_loop(5)}, {strand_across(5, 0.5)}, 0.5, {});
  ASSERT_EQ(out.size(), 1u);
  const Stroke& s = out[0];
  EXPECT_TRUE(s.start_mm.isApprox(Vec2(-5, 0))) << "starts on the loop, beside the strand";
  EXPECT_TRUE(s.end_mm().isApprox(Vec2(4.5, 0)));
  EXPECT_NEAR(slicer::stroke_length(s), 40 + 0.5 + 9, 1e-9) << "loop, link, strand";
}

TEST(PerimeterSplice, FarStrandOrBlockedLinkLeavesTheLoopAlone) {
  EXPECT_EQ(splice_loops({square_loop(5)}, {strand_across(5, 2.0)}, 0.5, {}).size(), 2u) << "too far";
  Stroke wall;  // a bead between the strand's end and the loop
  wall.start_mm = Vec2(-4.75, -1);
  wall.segments.push_back(slicer::line_to(Vec2(-4.75, 1), slicer::Feature::Wall));
  const auto right = splice_loops({square_loop(5)}, {strand_across(5, 0.5)}, 0.5, {wall});
  ASSERT_EQ(right.size(), 1u) << "the link at the left end is blocked: the right end takes the loop";
  EXPECT_TRUE(right[0].start_mm.isApprox(Vec2(-4.5, 0)));
  EXPECT_TRUE(right[0].end_mm().isApprox(Vec2(5, 0)));
  Stroke wall2 = wall;
  for (auto* p : {&wall2.start_mm, &wall2.segments[0].end_mm}) p->x() = 4.75;
  EXPECT_EQ(splice_loops({square_loop(5)}, {strand_across(5, 0.5)}, 0.5, {wall, wall2}).size(), 2u)
      << "both links blocked";
}

// A vertical strand at x from just inside the loop's bottom to just inside its top.
Stroke strand_up(double half, double gap, double x) {
  Stroke s;
  s.start_mm = Vec2(x, -half + gap);
  s.segments.push_back(slicer::line_to(Vec2(x, half - gap), slicer::Feature::Infill));
  return s;
}

TEST(PerimeterSplice, TwoStrandsEndingSideBySideBesideALoopBecomeOneThroughIt) {
  // Bottom ends two gaps (1 mm) apart along the loop: the first strand runs down, out to the
  // loop, round it the long way (39 of its 40 mm), back in and up the second.
  const auto out = splice_loops({square_loop(5)}, {strand_up(5, 0.5, -1), strand_up(5, 0.5, 0)}, 0.5, {});
  ASSERT_EQ(out.size(), 1u);
  EXPECT_TRUE(out[0].start_mm.isApprox(Vec2(-1, 4.5)));
  EXPECT_TRUE(out[0].end_mm().isApprox(Vec2(0, 4.5)));
  EXPECT_NEAR(slicer::stroke_length(out[0]), 9 + 0.5 + 39 + 0.5 + 9, 1e-9);
  // 3 mm apart, more than two gaps: the loop would lose too much; it joins the first strand
  // whole and the second stays a strand of its own.
  const auto far = splice_loops({square_loop(5)}, {strand_up(5, 0.5, -1), strand_up(5, 0.5, 2)}, 0.5, {});
  ASSERT_EQ(far.size(), 2u);
  EXPECT_NEAR(slicer::stroke_length(far[0]), 40 + 0.5 + 9, 1e-9);
}

}  // namespace
}  // namespace strand::patterns
