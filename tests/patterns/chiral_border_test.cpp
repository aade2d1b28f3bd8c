// Frame edges of chiral specimens: they make every node degree even and stay outside the
// attach circles, where the node passes live.
#include "patterns/chiral_border.h"

#include <gtest/gtest.h>

namespace strand::patterns {
namespace {

using slicer::Vec2;

std::vector<std::vector<double>> ligament_ends(const ChiralLattice& l, const NodeRings& r) {
  std::vector<std::vector<double>> ends(l.nodes.size());
  for (const auto& [a, b] : l.ligaments) {
    const auto pa = l.nodes[static_cast<std::size_t>(a)], pb = l.nodes[static_cast<std::size_t>(b)];
    const auto [ta, tb] = ligament_tangent(pa, pb, r.attach_mm);
    ends[static_cast<std::size_t>(a)].push_back(slicer::angle_of(pa, ta));
    ends[static_cast<std::size_t>(b)].push_back(slicer::angle_of(pb, tb));
  }
  return ends;
}

TEST(ChiralFrame, EvensEveryDegreeAndStaysOutsideTheNodes) {
  const NodeRings r = node_rings(2.0, 0.4, 0.32, 3);
  for (const ChiralLattice& l : {tetrachiral_lattice(2, 4, 8.0), tetrachiral_lattice(3, 3, 8.0),
                                 hexachiral_lattice(4, 5, 8.0), hexachiral_lattice(3, 4, 12.0)}) {
    const auto ends = ligament_ends(l, r);
    const ChiralFrame f = chiral_frame(l, r, ends, 0.4, 5.0);
    std::vector<std::size_t> degree(l.nodes.size());
    for (std::size_t v = 0; v < l.nodes.size(); ++v) degree[v] = ends[v].size();
    for (const auto& e : f.edges) {
      ++degree[static_cast<std::size_t>(e.from)], ++degree[static_cast<std::size_t>(e.to)];
      for (std::size_t k = 1; k + 1 < e.path.pts.size(); ++k) {
        for (const Vec2& c : l.nodes) EXPECT_GT((e.path.pts[k] - c).norm(), r.attach_mm);
      }
      EXPECT_NEAR((e.path.pts.front() - l.nodes[static_cast<std::size_t>(e.from)]).norm(),
                  r.attach_mm, 1e-9);
      EXPECT_NEAR((e.path.pts.back() - l.nodes[static_cast<std::size_t>(e.to)]).norm(), r.attach_mm,
                  1e-9);
    }
    for (std::size_t v = 0; v < degree.size(); ++v) EXPECT_EQ(degree[v] % 2, 0u) << "node " << v;
    ASSERT_GE(f.grip_edge, 0);
    EXPECT_LT(f.mark.y(), l.nodes.front().y() - r.frame_mm - 5.0 + 1e-9)
        << "mark under the bottom grip";
  }
}

}  // namespace
}  // namespace strand::patterns
