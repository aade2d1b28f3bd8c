// Non-crossing Euler circuits: every edge once, one curve on connected even graphs, and
// every visit pairs angularly adjacent ends.
#include "patterns/euler_circuit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace strand::patterns {
namespace {

// Grid of w x h vertices with 4-neighbour edges; odd border vertices paired by outer edges.
PlaneGraph grid_with_frame(int w, int h) {
  PlaneGraph g;
  g.vertex_count = w * h;
  auto id = [&](int i, int j) { return j * w + i; };
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      if (i + 1 < w) g.add_edge(id(i, j), id(i + 1, j), 0.0, M_PI);
      if (j + 1 < h) g.add_edge(id(i, j), id(i, j + 1), M_PI / 2, -M_PI / 2);
    }
  }
  // pair odd border vertices along each side with outer edges (angles pointing outward)
  for (int i = 1; i + 1 < w; i += 2) g.add_edge(id(i, 0), id(i + 1, 0), -M_PI / 2, -M_PI / 2);
  for (int i = 1; i + 1 < w; i += 2) g.add_edge(id(i, h - 1), id(i + 1, h - 1), M_PI / 2, M_PI / 2);
  for (int j = 1; j + 1 < h; j += 2) g.add_edge(id(0, j), id(0, j + 1), M_PI, M_PI);
  for (int j = 1; j + 1 < h; j += 2) g.add_edge(id(w - 1, j), id(w - 1, j + 1), 0.0, 0.0);
  return g;
}

TEST(NoncrossingCircuits, ConnectedEvenGridIsOneCurveUsingEveryEdgeOnce) {
  const PlaneGraph g = grid_with_frame(6, 8);  // w - 2, h - 2 even: border vertices pair up
  const auto curves = noncrossing_circuits(g);
  ASSERT_EQ(curves.size(), 1u);
  std::set<int> used;
  for (const auto& s : curves[0]) EXPECT_TRUE(used.insert(s.edge).second) << "edge twice";
  EXPECT_EQ(used.size(), g.edge_from.size());
  // consecutive steps meet at a vertex
  const auto& c = curves[0];
  for (std::size_t k = 0; k < c.size(); ++k) {
    const auto& a = c[k];
    const auto& b = c[(k + 1) % c.size()];
    const int end_a = a.forward ? g.edge_to[a.edge] : g.edge_from[a.edge];
    const int start_b = b.forward ? g.edge_from[b.edge] : g.edge_to[b.edge];
    EXPECT_EQ(end_a, start_b);
  }
}

TEST(NoncrossingCircuits, VisitsPairAngularNeighbours) {
  const PlaneGraph g = grid_with_frame(6, 6);
  const auto c = noncrossing_circuits(g).at(0);
  for (std::size_t k = 0; k < c.size(); ++k) {
    const auto& a = c[k];
    const auto& b = c[(k + 1) % c.size()];
    const double in = a.forward ? g.angle_to_rad[a.edge] : g.angle_from_rad[a.edge];
    const double out = b.forward ? g.angle_from_rad[b.edge] : g.angle_to_rad[b.edge];
    const double diff = std::remainder(out - in, 2 * M_PI);
    EXPECT_NEAR(std::abs(diff), M_PI / 2, 1e-9) << "interior vertices have ends 90 deg apart";
  }
}

TEST(NoncrossingCircuits, OddDegreeIsALogicError) {
  PlaneGraph g;
  g.vertex_count = 2;
  g.add_edge(0, 1, 0, 0);
  EXPECT_THROW(noncrossing_circuits(g), std::logic_error);
}

}  // namespace
}  // namespace strand::patterns
