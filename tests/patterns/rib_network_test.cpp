// Non-crossing circuits: every edge once, passes through a shared vertex never interleave,
// circuits merged where they meet, odd degree refused.
#include "patterns/rib_network.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "slicer/units.h"

namespace strand::patterns {
namespace {

using slicer::Vec2;

void add_square(RibNetwork& net, int corner, const Vec2& a, const Vec2& b, const Vec2& c) {
  const int va = net.add_vertex(a), vb = net.add_vertex(b), vc = net.add_vertex(c);
  net.add_edge(corner, va, slicer::Feature::Ligament);
  net.add_edge(va, vb, slicer::Feature::Ligament);
  net.add_edge(vb, vc, slicer::Feature::Ligament);
  net.add_edge(vc, corner, slicer::Feature::Ligament);
}

// Two squares touching at the origin: a figure of eight.
RibNetwork figure_eight() {
  RibNetwork net;
  const int o = net.add_vertex(Vec2(0, 0));
  add_square(net, o, Vec2(1, 0), Vec2(1, 1), Vec2(0, 1));
  add_square(net, o, Vec2(-1, 0), Vec2(-1, -1), Vec2(0, -1));
  return net;
}

// Angles (deg, [0, 360)) of the two edges used by each pass through `v` in a closed stroke.
std::vector<std::pair<double, double>> passes_through(const slicer::Stroke& s, const Vec2& v) {
  std::vector<Vec2> pts{s.start_mm};
  for (const auto& seg : s.segments) pts.push_back(seg.end_mm);
  const std::size_t n = pts.size() - 1;  // closed: pts[n] == pts[0]
  auto angle = [&](const Vec2& q) {
    const double a = std::atan2(q.y() - v.y(), q.x() - v.x()) * 180.0 / slicer::kPi;
    return a < 0 ? a + 360 : a;
  };
  std::vector<std::pair<double, double>> out;
  for (std::size_t i = 0; i < n; ++i) {
    if ((pts[i] - v).norm() > 1e-12) continue;
    const Vec2& before = pts[i == 0 ? n - 1 : i - 1];
    out.emplace_back(angle(before), angle(pts[i + 1]));
  }
  return out;
}

bool interleave(std::pair<double, double> p, std::pair<double, double> q) {
  auto inside = [](double lo, double hi, double x) { return std::min(lo, hi) < x && x < std::max(lo, hi); };
  return inside(p.first, p.second, q.first) != inside(p.first, p.second, q.second);
}

TEST(RibNetwork, FigureEightIsOneCircuitThatTurnsAtTheSharedVertex) {
  const RibNetwork net = figure_eight();
  const auto strokes = non_crossing_circuits(net);
  ASSERT_EQ(strokes.size(), 1u);
  EXPECT_EQ(strokes[0].segments.size(), net.edges.size());
  EXPECT_LT((strokes[0].end_mm() - strokes[0].start_mm).norm(), 1e-12) << "closed";
  const auto passes = passes_through(strokes[0], Vec2(0, 0));
  ASSERT_EQ(passes.size(), 2u);
  EXPECT_FALSE(interleave(passes[0], passes[1]))
      << "(" << passes[0].first << "," << passes[0].second << ") vs (" << passes[1].first << ","
      << passes[1].second << ")";
}

TEST(RibNetwork, DisjointPiecesGiveOneStrandEach) {
  RibNetwork net;
  add_square(net, net.add_vertex(Vec2(0, 0)), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1));
  add_square(net, net.add_vertex(Vec2(5, 0)), Vec2(6, 0), Vec2(6, 1), Vec2(5, 1));
  EXPECT_EQ(non_crossing_circuits(net).size(), 2u);
}

TEST(RibNetwork, OddDegreeIsAProgrammingError) {
  RibNetwork net = figure_eight();
  net.add_edge(1, 2, slicer::Feature::Frame);  // a diagonal: two odd vertices
  EXPECT_THROW(non_crossing_circuits(net), std::logic_error);
}

}  // namespace
}  // namespace strand::patterns
