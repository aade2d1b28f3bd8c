// Tangent construction, pass radii and clearances of chiral lattices.
#include "patterns/chiral_lattice.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "slicer/units.h"

namespace strand::patterns {
namespace {

using slicer::Vec2;

TEST(LigamentTangent, TouchesBothCirclesAndPassesThroughTheMidpoint) {
  for (double deg : {0.0, 37.0, 90.0, 200.0}) {
    const Vec2 a(1, 2),
        b = a + 7.0 * Vec2(std::cos(slicer::deg_to_rad(deg)), std::sin(slicer::deg_to_rad(deg)));
    const double r = 1.6;
    const auto [ta, tb] = ligament_tangent(a, b, r);
    EXPECT_NEAR((ta - a).norm(), r, 1e-12);
    EXPECT_NEAR((tb - b).norm(), r, 1e-12);
    EXPECT_NEAR((ta - a).dot(tb - ta), 0.0, 1e-9) << "tangent at a";
    EXPECT_NEAR((tb - b).dot(tb - ta), 0.0, 1e-9) << "tangent at b";
    EXPECT_NEAR(slicer::point_segment_distance((a + b) / 2, ta, tb), 0.0, 1e-12)
        << "internal tangent";
    EXPECT_GT(slicer::cross(ta - a, tb - ta), 0.0) << "leaves a counter-clockwise";
  }
}

TEST(LigamentTangent, AngleMatchesTheThesisExample) {
  // l = 10, r = 1.6: tangent points at -71.3 deg around the left node (analysis note).
  const auto [ta, tb] = ligament_tangent(Vec2(0, 0), Vec2(10, 0), 1.6);
  EXPECT_NEAR(slicer::rad_to_deg(std::atan2(ta.y(), ta.x())), -71.34, 0.01);
  EXPECT_NEAR(slicer::rad_to_deg(ligament_angle_rad(10, 1.6)), 18.66, 0.01);
}

TEST(NodeRings, ThreePassesAreRMinusHRAndRPlusH) {
  const NodeRings r = node_rings(1.87, 0.5, 0.4, 3);
  const double mid = 1.87 / 2 + 0.4 + 0.5 / 2;
  ASSERT_EQ(r.pass_mm.size(), 3u);
  EXPECT_NEAR(r.pass_mm[0], mid - 0.4, 1e-12);
  EXPECT_NEAR(r.pass_mm[1], mid, 1e-12);
  EXPECT_NEAR(r.pass_mm[2], mid + 0.4, 1e-12);
  EXPECT_NEAR(r.middle_mm, mid, 1e-12);
  EXPECT_NEAR(r.attach_mm, mid + 2 * 0.4, 1e-12) << "the thesis routes ligaments at r + 2h";
  EXPECT_NEAR(r.ring_width_mm, 2 * 0.4 + 0.5, 1e-12);
}

TEST(NodeRings, InnerPassKeepsTheCoreForAnyPassCount) {
  for (int n : {1, 3, 5, 7}) {
    const NodeRings r = node_rings(2.0, 0.4, 0.32, n);
    EXPECT_NEAR(r.pass_mm.front(), 1.0 + 0.2, 1e-12);
    EXPECT_NEAR(r.pass_mm.back() - r.pass_mm.front(), (n - 1) * 0.32, 1e-12);
  }
}

TEST(MinCell, IsTheBoundaryOfTheClearanceRule) {
  const NodeRings r = node_rings(1.87, 0.5, 0.4, 3);
  const double lo = min_cell_mm(&tetrachiral_lattice, r, 0.5);
  const Clearance ok = lattice_clearance(tetrachiral_lattice(3, 3, lo), r);
  EXPECT_GE(std::min(ok.node_mm, ok.ligament_mm), 0.5);
  EXPECT_GE(std::sqrt(lo * lo - 4 * r.attach_mm * r.attach_mm), 0.5) << "ligament one bead long";
  const double below = lo - 0.02;
  const Clearance bad = lattice_clearance(tetrachiral_lattice(3, 3, below), r);
  const double ligament = std::sqrt(below * below - 4 * r.attach_mm * r.attach_mm);
  EXPECT_LT(std::min({bad.node_mm, bad.ligament_mm, ligament}), 0.5);
}

TEST(BorderPolygon, OffsetsStraightSidesByTheOffset) {
  const ChiralLattice l = tetrachiral_lattice(2, 2, 10);
  const auto poly = border_polygon(l, 3);
  ASSERT_EQ(poly.size(), l.boundary.size());
  EXPECT_NEAR(poly[1].y(), -13.0, 1e-12);  // bottom middle node at y = -10
  EXPECT_NEAR(poly[0].x(), -13.0, 1e-12);  // corner mitre
  EXPECT_NEAR(poly[0].y(), -13.0, 1e-12);
}

}  // namespace
}  // namespace strand::patterns
