// Non-crossing Euler circuits: cyclic pairing of edge ends at each vertex, then merging of
// the resulting circuits by re-pairing at degree-4 vertices (union-find keeps track).
#include "patterns/rib_network.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace strand::patterns {

using slicer::Vec2;

int RibNetwork::add_vertex(const Vec2& p_mm) {
  vertices_mm.push_back(p_mm);
  return static_cast<int>(vertices_mm.size()) - 1;
}

void RibNetwork::add_edge(int a, int b, slicer::Feature feature, int wrap) {
  edges.push_back({a, b, feature, wrap});
}

namespace {

// Edge end k belongs to edge k / 2; it sits at the edge's a (k even) or b (k odd) vertex.
struct Ends {
  const RibNetwork& net;
  int vertex(int k) const {
    const auto& e = net.edges[static_cast<std::size_t>(k / 2)];
    return k % 2 == 0 ? e.a : e.b;
  }
  // Periods between this end's vertex and the far vertex's copy the edge reaches.
  int shift(int k) const {
    const int w = net.edges[static_cast<std::size_t>(k / 2)].wrap;
    return k % 2 == 0 ? w : -w;
  }
  Vec2 at(int k) const { return net.vertices_mm[static_cast<std::size_t>(vertex(k))]; }
  // The far vertex as the edge reaches it, in the frame of this end's vertex.
  Vec2 far(int k) const { return at(k ^ 1) + Vec2(shift(k) * net.period_mm, 0.0); }
  // Direction of the edge as seen from this end's vertex.
  double angle(int k) const {
    const Vec2 d = far(k) - at(k);
    return std::atan2(d.y(), d.x());
  }
};

// Edge ends around every vertex, counter-clockwise by direction.
std::vector<std::vector<int>> ends_around(const RibNetwork& net) {
  const Ends ends{net};
  std::vector<std::vector<int>> around(net.vertices_mm.size());
  for (int k = 0; k < static_cast<int>(2 * net.edges.size()); ++k) {
    around[static_cast<std::size_t>(ends.vertex(k))].push_back(k);
  }
  for (std::size_t v = 0; v < around.size(); ++v) {
    auto& list = around[v];
    if (list.size() % 2 != 0) {
      throw std::logic_error("non_crossing_circuits: vertex " + std::to_string(v) + " has odd degree");
    }
    std::sort(list.begin(), list.end(), [&](int x, int y) { return ends.angle(x) < ends.angle(y); });
  }
  return around;
}

// Circuit label of every edge end under the pairing `partner` (leave by k, arrive by k^1).
std::vector<int> label_circuits(const std::vector<int>& partner) {
  std::vector<int> label(partner.size(), -1);
  int next = 0;
  for (std::size_t s = 0; s < partner.size(); ++s) {
    if (label[s] >= 0) continue;
    int cur = static_cast<int>(s);
    do {
      label[static_cast<std::size_t>(cur)] = label[static_cast<std::size_t>(cur ^ 1)] = next;
      cur = partner[static_cast<std::size_t>(cur ^ 1)];
    } while (cur != static_cast<int>(s));
    ++next;
  }
  return label;
}

int find_root(std::vector<int>& parent, int x) {
  while (parent[static_cast<std::size_t>(x)] != x) {
    x = parent[static_cast<std::size_t>(x)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
  }
  return x;
}

// Switches the pairing at degree-4 vertices where two different circuits meet.
void merge_circuits(const std::vector<std::vector<int>>& around, std::vector<int>& partner) {
  const std::vector<int> label = label_circuits(partner);
  std::vector<int> parent(label.size());
  std::iota(parent.begin(), parent.end(), 0);
  for (const auto& list : around) {
    if (list.size() != 4) continue;
    const int c0 = find_root(parent, label[static_cast<std::size_t>(list[0])]);
    const int c2 = find_root(parent, label[static_cast<std::size_t>(list[2])]);
    if (c0 == c2) continue;
    auto pair = [&](int x, int y) {
      partner[static_cast<std::size_t>(x)] = y;
      partner[static_cast<std::size_t>(y)] = x;
    };
    pair(list[1], list[2]);
    pair(list[3], list[0]);
    parent[static_cast<std::size_t>(c0)] = c2;
  }
}

// The points a pass through vertex v puts down: v itself, or the two ends of the corner cut
// that keeps it `gap / 2` from v, on the arriving edge then on the leaving edge.
std::vector<Vec2> pass_points(const Ends& ends, int arrive, int leave, bool cut, double gap) {
  const Vec2 v = ends.at(leave);
  if (!cut) return {v};
  const Vec2 in = (ends.far(arrive) - v).normalized();
  const Vec2 out = (ends.far(leave) - v).normalized();
  const double half_wedge = std::acos(std::clamp(in.dot(out), -1.0, 1.0)) / 2;
  const double along = gap / 2 / std::max(std::cos(half_wedge), 1e-3);
  return {v + along * in, v + along * out};
}

// One closed stroke along the leaving ends; corner cuts are Node segments. `periods` counts
// how far (in periods) the strand has run past the seam, so each vertex is drawn where the
// strand reaches it.
template <class IsNode>
slicer::Stroke trace(const RibNetwork& net, const Ends& ends, const std::vector<int>& leaving,
                     const IsNode& is_node, double gap) {
  const std::size_t m = leaving.size();
  auto points_at = [&](std::size_t i, int periods) {
    const int leave = leaving[i % m];
    const int arrive = leaving[(i + m - 1) % m] ^ 1;
    std::vector<Vec2> pts = pass_points(ends, arrive, leave, gap > 0 && is_node(leave), gap);
    for (Vec2& p : pts) p.x() += periods * net.period_mm;
    return pts;
  };
  auto feature_of = [&](int end) { return net.edges[static_cast<std::size_t>(end / 2)].feature; };
  slicer::Stroke stroke;
  stroke.start_mm = points_at(0, 0).back();
  int periods = 0;
  for (std::size_t i = 1; i <= m; ++i) {
    periods += ends.shift(leaving[i - 1]);
    const std::vector<Vec2> pts = points_at(i, periods);
    stroke.segments.push_back(slicer::line_to(pts.front(), feature_of(leaving[i - 1])));
    if (pts.size() == 2) stroke.segments.push_back(slicer::line_to(pts.back(), slicer::Feature::Node));
  }
  return stroke;
}

}  // namespace

std::vector<slicer::Stroke> non_crossing_circuits(const RibNetwork& net, double node_gap_mm) {
  const auto around = ends_around(net);
  std::vector<int> partner(2 * net.edges.size(), -1);
  for (const auto& list : around) {
    for (std::size_t i = 0; i + 1 < list.size(); i += 2) {
      partner[static_cast<std::size_t>(list[i])] = list[i + 1];
      partner[static_cast<std::size_t>(list[i + 1])] = list[i];
    }
  }
  merge_circuits(around, partner);
  const Ends ends{net};
  auto is_node = [&](int end) { return around[static_cast<std::size_t>(ends.vertex(end))].size() >= 4; };
  std::vector<bool> used(partner.size(), false);
  std::vector<slicer::Stroke> out;
  for (std::size_t v = 0; v < around.size(); ++v) {
    for (int s : around[v]) {
      if (used[static_cast<std::size_t>(s)]) continue;
      std::vector<int> leaving;  // leaving ends in traversal order
      for (int cur = s;;) {
        used[static_cast<std::size_t>(cur)] = used[static_cast<std::size_t>(cur ^ 1)] = true;
        leaving.push_back(cur);
        cur = partner[static_cast<std::size_t>(cur ^ 1)];
        if (cur == s) break;
      }
      const auto first_plain = std::find_if(leaving.begin(), leaving.end(), [&](int e) { return !is_node(e); });
      if (first_plain != leaving.end()) std::rotate(leaving.begin(), first_plain, leaving.end());
      out.push_back(trace(net, ends, leaving, is_node, node_gap_mm));
    }
  }
  return out;
}

}  // namespace strand::patterns
