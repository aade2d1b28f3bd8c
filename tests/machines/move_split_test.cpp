// Cutting lines and arcs: pieces end on the path and share the volume by length.
#include "machines/move_split.h"

#include <gtest/gtest.h>

#include <cmath>

namespace strand::machines {
namespace {

TEST(MoveSplit, LineCutsAreOnTheLineAndVolumesSum) {
  slicer::Move m;
  m.kind = slicer::MoveKind::Deposit;
  m.end_mm = {10, 0, 1};
  m.volume_mm3 = 4.0;
  const auto p = split_move({0, 0, 1}, m, {0.25, 0.5});
  ASSERT_EQ(p.size(), 3u);
  EXPECT_NEAR(p[0].end_mm.x(), 2.5, 1e-12);
  EXPECT_NEAR(p[1].end_mm.x(), 5.0, 1e-12);
  EXPECT_EQ(p[2].end_mm, m.end_mm);
  EXPECT_NEAR(p[0].volume_mm3 + p[1].volume_mm3 + p[2].volume_mm3, 4.0, 1e-12);
  EXPECT_NEAR(p[2].volume_mm3, 2.0, 1e-12);
}

TEST(MoveSplit, ArcHalfwayIsOnTheCircle) {
  // Quarter circle radius 5 around the origin from (5,0) ccw to (0,5): halfway at 45 deg.
  slicer::Move m;
  m.kind = slicer::MoveKind::Deposit;
  m.is_arc = true;
  m.ccw = true;
  m.center_mm = {0, 0};
  m.end_mm = {0, 5, 0};
  const auto q = point_along({5, 0, 0}, m, 0.5);
  EXPECT_NEAR(q.x(), 5 / std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(q.y(), 5 / std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(path_length({5, 0, 0}, m), 5 * M_PI / 2, 1e-9);
}

}  // namespace
}  // namespace strand::machines
