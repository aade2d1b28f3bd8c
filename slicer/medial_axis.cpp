// Medial axis through Boost.Polygon's Voronoi diagram of the boundary segments: the inner
// primary edges, clipped to the width band, pruned of corner spurs, chained at forks.
#include "slicer/medial_axis.h"

#include <algorithm>
#include <boost/polygon/segment_data.hpp>
#include <boost/polygon/voronoi.hpp>
#include <cmath>
#include <limits>

#include "slicer/tolerances.h"

namespace strand::slicer {

namespace {

namespace bp = boost::polygon;
using Diagram = bp::voronoi_diagram<double>;
using InputSegment = bp::segment_data<int>;

// The graph of the kept medial axis: nodes with their local width, edges between them.
struct AxisGraph {
  std::vector<Vec2> pos;
  std::vector<double> width;
  std::vector<std::pair<int, int>> edges;
  std::vector<bool> alive;
  std::vector<std::vector<int>> incident;  // per node, its edges (alive or not)

  int add_node(const Vec2& p, double w) {
    pos.push_back(p);
    width.push_back(w);
    incident.emplace_back();
    return static_cast<int>(pos.size()) - 1;
  }
  void add_edge(int a, int b) {
    edges.emplace_back(a, b);
    alive.push_back(true);
    incident[a].push_back(static_cast<int>(edges.size()) - 1);
    incident[b].push_back(static_cast<int>(edges.size()) - 1);
  }
  int other(int e, int n) const { return edges[e].first == n ? edges[e].second : edges[e].first; }
  int degree(int n) const {
    int d = 0;
    for (int e : incident[n]) d += alive[e] ? 1 : 0;
    return d;
  }
  std::vector<int> live_edges(int n) const {
    std::vector<int> out;
    for (int e : incident[n]) if (alive[e]) out.push_back(e);
    return out;
  }
  double length(int e) const { return (pos[edges[e].first] - pos[edges[e].second]).norm(); }
};

// The diagram's input: every ring's edges in integer units around the region's centre.
struct Input {
  std::vector<InputSegment> segments;
  Vec2 origin = Vec2::Zero();
  Vec2 to_mm(double x, double y) const { return origin + Vec2(x, y) / kClipperUnitsPerMm; }
};

bool make_input(const Region& region, std::size_t max_segments, Input& in) {
  const auto [lo, hi] = region_bounds(region);
  // On the Clipper grid, so the region's points (on it too) stay exact integers.
  in.origin = ((lo + hi) / 2.0 * kClipperUnitsPerMm).array().round() / kClipperUnitsPerMm;
  // int coordinates: the region must fit +-2^31 units around its centre.
  if ((hi - lo).maxCoeff() * kClipperUnitsPerMm / 2.0 > 2.0e9) return false;
  for (const Ring& ring : rings_of(region)) {
    std::vector<bp::point_data<int>> pts;
    for (const Vec2& v : ring) {
      const Vec2 q = (v - in.origin) * kClipperUnitsPerMm;
      bp::point_data<int> p(static_cast<int>(std::lround(q.x())), static_cast<int>(std::lround(q.y())));
      if (pts.empty() || pts.back() != p) pts.push_back(p);
    }
    while (pts.size() > 1 && pts.front() == pts.back()) pts.pop_back();
    if (pts.size() < 3) continue;
    for (std::size_t i = 0; i < pts.size(); ++i) in.segments.emplace_back(pts[i], pts[(i + 1) % pts.size()]);
    if (in.segments.size() > max_segments) return false;
  }
  return !in.segments.empty();
}

Vec2 seg_start(const Input& in, const InputSegment& s) { return in.to_mm(bp::low(s).x(), bp::low(s).y()); }
Vec2 seg_end(const Input& in, const InputSegment& s) { return in.to_mm(bp::high(s).x(), bp::high(s).y()); }

// Distance from p to the site of `cell` (a boundary segment or one of its end points).
double site_distance(const Input& in, const Diagram::cell_type& cell, const Vec2& p) {
  const InputSegment& s = in.segments[cell.source_index()];
  if (cell.contains_segment()) return point_segment_distance(p, seg_start(in, s), seg_end(in, s));
  const Vec2 q = cell.source_category() == bp::SOURCE_CATEGORY_SEGMENT_START_POINT
                     ? seg_start(in, s) : seg_end(in, s);
  return (p - q).norm();
}

// Whether the edge a-b of the diagram lies inside the region: rings keep the inside on their
// left, so an edge in a segment's cell is inside when it lies left of that segment.
bool inside(const Input& in, const Region& region, const Diagram::edge_type& e, const Vec2& mid) {
  for (const Diagram::cell_type* c : {e.cell(), e.twin()->cell()}) {
    if (!c->contains_segment()) continue;
    const InputSegment& s = in.segments[c->source_index()];
    const Vec2 a = seg_start(in, s), b = seg_end(in, s);
    return cross(b - a, mid - a) > 0.0;
  }
  return contains(region, mid);  // between two corners: rare, tested directly
}

// The diagram's inner edges, each clipped to the width band, as a graph.
AxisGraph axis_graph(const Region& region, const Input& in, const MedialAxisLimits& lim) {
  Diagram vd;
  bp::construct_voronoi(in.segments.begin(), in.segments.end(), &vd);
  AxisGraph g;
  std::vector<int> node_of(vd.num_vertices(), -1);
  const Diagram::vertex_type* first = vd.num_vertices() ? &vd.vertices()[0] : nullptr;
  auto vertex_node = [&](const Diagram::vertex_type* v, const Vec2& p, double w) {
    int& n = node_of[static_cast<std::size_t>(v - first)];
    if (n < 0) n = g.add_node(p, w);
    return n;
  };
  for (std::size_t i = 0; i < vd.edges().size(); i += 2) {  // an edge and its twin are adjacent
    const Diagram::edge_type& e = vd.edges()[i];
    if (!e.is_primary() || !e.is_finite()) continue;
    const Vec2 p0 = in.to_mm(e.vertex0()->x(), e.vertex0()->y());
    const Vec2 p1 = in.to_mm(e.vertex1()->x(), e.vertex1()->y());
    if (!inside(in, region, e, (p0 + p1) / 2.0)) continue;
    const double w0 = 2.0 * site_distance(in, *e.cell(), p0);
    const double w1 = 2.0 * site_distance(in, *e.cell(), p1);
    // Parameters along the edge where the (linearly interpolated) width is in the band.
    double t0 = 0.0, t1 = 1.0;
    for (const double bound : {lim.min_width_mm, lim.max_width_mm}) {
      const bool is_min = bound == lim.min_width_mm;
      const bool out0 = is_min ? w0 < bound : w0 > bound, out1 = is_min ? w1 < bound : w1 > bound;
      if (out0 && out1) t0 = 1.0, t1 = 0.0;
      else if (out0) t0 = std::max(t0, (bound - w0) / (w1 - w0));
      else if (out1) t1 = std::min(t1, (bound - w0) / (w1 - w0));
    }
    if (t1 - t0 <= 0.0 || (p1 - p0).norm() * (t1 - t0) < kSamePointMm) continue;
    const int a = t0 > 0.0 ? g.add_node(p0 + t0 * (p1 - p0), w0 + t0 * (w1 - w0))
                           : vertex_node(e.vertex0(), p0, w0);
    const int b = t1 < 1.0 ? g.add_node(p0 + t1 * (p1 - p0), w0 + t1 * (w1 - w0))
                           : vertex_node(e.vertex1(), p1, w1);
    if (a != b) g.add_edge(a, b);
  }
  return g;
}

struct Branch {
  std::vector<int> edges;
  double length = 0.0;
  int fork = -1;  // the node of degree >= 3 it ends at
};

// From leaf `n` along nodes of degree 2 to a fork (fork = -1 when it reaches another leaf).
Branch walk_branch(const AxisGraph& g, int n) {
  Branch b;
  int e = g.live_edges(n).front();
  for (;;) {
    b.edges.push_back(e);
    b.length += g.length(e);
    n = g.other(e, n);
    const std::vector<int> next = g.live_edges(n);
    if (next.size() >= 3) return b.fork = n, b;
    if (next.size() != 2) return b;
    e = next[0] == e ? next[1] : next[0];
  }
}

// Removes the branches from a free end to a fork shorter than the width at the fork (the
// spurs into corners), keeping the two longest where every branch of a fork is such a spur.
void prune_spurs(AxisGraph& g) {
  for (int pass = 0; pass < 64; ++pass) {
    std::vector<std::vector<Branch>> at_fork(g.pos.size());
    for (int n = 0; n < static_cast<int>(g.pos.size()); ++n) {
      if (g.degree(n) != 1) continue;
      Branch b = walk_branch(g, n);
      if (b.fork >= 0 && b.length < g.width[b.fork]) at_fork[b.fork].push_back(std::move(b));
    }
    bool changed = false;
    for (int f = 0; f < static_cast<int>(g.pos.size()); ++f) {
      std::vector<Branch>& spurs = at_fork[f];
      if (spurs.empty()) continue;
      if (static_cast<int>(spurs.size()) == g.degree(f)) {
        std::stable_sort(spurs.begin(), spurs.end(),
                         [](const Branch& a, const Branch& b) { return a.length > b.length; });
        spurs.erase(spurs.begin(), spurs.begin() + 2);
      }
      for (const Branch& b : spurs) {
        for (int e : b.edges) g.alive[e] = false;
        changed = true;
      }
    }
    if (!changed) return;
  }
}

// At each fork, the two edges that continue each other most nearly straight.
std::vector<std::pair<int, int>> straightest_pairs(const AxisGraph& g) {
  std::vector<std::pair<int, int>> pair_at(g.pos.size(), {-1, -1});
  for (int n = 0; n < static_cast<int>(g.pos.size()); ++n) {
    const std::vector<int> es = g.live_edges(n);
    if (es.size() < 3) continue;
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < es.size(); ++i) {
      for (std::size_t j = i + 1; j < es.size(); ++j) {
        const Vec2 a = (g.pos[g.other(es[i], n)] - g.pos[n]).normalized();
        const Vec2 b = (g.pos[g.other(es[j], n)] - g.pos[n]).normalized();
        if (a.dot(b) < best) best = a.dot(b), pair_at[n] = {es[i], es[j]};
      }
    }
  }
  return pair_at;
}

// The live edges chained into polylines: through nodes of degree 2 and through each fork's
// straightest pair; what is left over (cycles) closes on itself.
std::vector<CentreLine> chain(const AxisGraph& g) {
  const std::vector<std::pair<int, int>> pair_at = straightest_pairs(g);
  std::vector<bool> used(g.edges.size(), false);
  auto next_edge = [&](int e, int n) {
    const std::vector<int> es = g.live_edges(n);
    if (es.size() == 2) return es[0] == e ? es[1] : es[0];
    const auto [a, b] = pair_at[n];
    return e == a ? b : e == b ? a : -1;
  };
  auto walk = [&](int n, int e) {
    CentreLine line;
    line.points.push_back(g.pos[n]);
    line.width_mm.push_back(g.width[n]);
    while (e >= 0 && !used[e]) {
      used[e] = true;
      n = g.other(e, n);
      line.points.push_back(g.pos[n]);
      line.width_mm.push_back(g.width[n]);
      e = next_edge(e, n);
    }
    return line;
  };
  std::vector<CentreLine> out;
  for (int n = 0; n < static_cast<int>(g.pos.size()); ++n) {
    if (g.degree(n) == 2) continue;
    for (int e : g.live_edges(n)) {
      if (!used[e] && next_edge(e, n) < 0) out.push_back(walk(n, e));
    }
  }
  for (int e = 0; e < static_cast<int>(g.edges.size()); ++e) {
    if (g.alive[e] && !used[e]) out.push_back(walk(g.edges[e].first, e));
  }
  return out;
}

}  // namespace

double polyline_length_mm(const std::vector<Vec2>& points) {
  double len = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) len += (points[i] - points[i - 1]).norm();
  return len;
}

std::vector<CentreLine> centre_lines(const Region& region, const MedialAxisLimits& limits) {
  Input in;
  if (region.empty() || !make_input(region, limits.max_segments, in)) return {};
  AxisGraph g = axis_graph(region, in, limits);
  prune_spurs(g);
  std::vector<CentreLine> out;
  for (CentreLine& line : chain(g)) {
    // A piece no longer than its own width is a corner's bisector cut out by the band, not a
    // feature.
    const double widest = *std::max_element(line.width_mm.begin(), line.width_mm.end());
    const double len = polyline_length_mm(line.points);
    if (len >= limits.min_length_mm && len > widest) out.push_back(std::move(line));
  }
  return out;
}

}  // namespace strand::slicer
