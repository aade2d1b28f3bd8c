// Clipping polylines against rings with exact, consistent crossing predicates and a grid.
#include "patterns/region_clip.h"

#include <algorithm>
#include <cmath>

namespace strand::patterns {

using slicer::Vec2;

namespace {

// Side of p from the directed line a -> b; a point on the line counts as left (+1), the
// same way wherever the predicate is evaluated, so crossings pair up.
int side(const Vec2& a, const Vec2& b, const Vec2& p) {
  return slicer::cross(b - a, p - a) >= 0.0 ? 1 : -1;
}

bool crosses(const Vec2& p0, const Vec2& p1, const Vec2& a, const Vec2& b) {
  return side(a, b, p0) != side(a, b, p1) && side(p0, p1, a) != side(p0, p1, b);
}

struct EdgeRef {
  int ring = 0;
  int edge = 0;
};

// Ring edges bucketed in a uniform grid; each query visits the cells a segment's box covers.
class EdgeGrid {
 public:
  explicit EdgeGrid(const RingSet& rs) {
    std::size_t count = 0;
    double length = 0.0;
    bool first = true;
    for (const auto& ring : rs.rings) {
      for (const Vec2& v : ring) {
        lo_ = first ? v : lo_.cwiseMin(v);
        hi_ = first ? v : hi_.cwiseMax(v);
        first = false;
      }
      count += ring.size();
    }
    for (std::size_t r = 0; r < rs.rings.size(); ++r) length += rs.s_mm[r].back();
    const Vec2 size = (hi_ - lo_).cwiseMax(Vec2(1e-6, 1e-6));
    cell_ = std::max(
        {count ? 2.0 * length / static_cast<double>(count) : 1.0, size.maxCoeff() / 512.0, 1e-6});
    nx_ = static_cast<int>(size.x() / cell_) + 1;
    ny_ = static_cast<int>(size.y() / cell_) + 1;
    cells_.resize(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_));
    stamp_.resize(rs.rings.size());
    for (std::size_t r = 0; r < rs.rings.size(); ++r) {
      const auto& ring = rs.rings[r];
      stamp_[r].assign(ring.size(), 0);
      for (std::size_t i = 0; i < ring.size(); ++i) {
        visit(ring[i], ring[(i + 1) % ring.size()], [&](std::vector<EdgeRef>& cell) {
          cell.push_back({static_cast<int>(r), static_cast<int>(i)});
        });
      }
    }
  }

  // Calls f(ring, edge) once for every edge near the segment p0-p1.
  template <typename F>
  void near(const Vec2& p0, const Vec2& p1, F f) {
    ++query_;
    visit(p0, p1, [&](std::vector<EdgeRef>& cell) {
      for (const EdgeRef& e : cell) {
        auto& st = stamp_[static_cast<std::size_t>(e.ring)][static_cast<std::size_t>(e.edge)];
        if (st == query_) continue;
        st = query_;
        f(e.ring, e.edge);
      }
    });
  }

 private:
  template <typename F>
  void visit(const Vec2& a, const Vec2& b, F f) {
    const Vec2 lo = a.cwiseMin(b), hi = a.cwiseMax(b);
    const int x0 = std::clamp(static_cast<int>(std::floor((lo.x() - lo_.x()) / cell_)), 0, nx_ - 1);
    const int x1 = std::clamp(static_cast<int>(std::floor((hi.x() - lo_.x()) / cell_)), 0, nx_ - 1);
    const int y0 = std::clamp(static_cast<int>(std::floor((lo.y() - lo_.y()) / cell_)), 0, ny_ - 1);
    const int y1 = std::clamp(static_cast<int>(std::floor((hi.y() - lo_.y()) / cell_)), 0, ny_ - 1);
    if (hi.x() < lo_.x() || hi.y() < lo_.y() || lo.x() > hi_.x() || lo.y() > hi_.y()) return;
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) f(cells_[static_cast<std::size_t>(y) * nx_ + x]);
    }
  }

  Vec2 lo_ = Vec2::Zero(), hi_ = Vec2::Zero();
  double cell_ = 1.0;
  int nx_ = 1, ny_ = 1;
  std::vector<std::vector<EdgeRef>> cells_;
  std::vector<std::vector<unsigned>> stamp_;
  unsigned query_ = 0;
};

struct Cut {
  double t = 0.0;  // along the pattern segment
  RingSpot spot;
  Vec2 at = Vec2::Zero();
};

// Cuts of segment p0-p1 with the rings, in order along the segment.
std::vector<Cut> cuts_of(const RingSet& rs, EdgeGrid& grid, const Vec2& p0, const Vec2& p1) {
  std::vector<Cut> cuts;
  grid.near(p0, p1, [&](int r, int i) {
    const auto& ring = rs.rings[static_cast<std::size_t>(r)];
    const Vec2& a = ring[static_cast<std::size_t>(i)];
    const Vec2& b = ring[(static_cast<std::size_t>(i) + 1) % ring.size()];
    if (!crosses(p0, p1, a, b)) return;
    const Vec2 d = p1 - p0, e = b - a;
    const double den = slicer::cross(d, e);
    const double t = den == 0.0 ? 0.0 : std::clamp(slicer::cross(a - p0, e) / den, 0.0, 1.0);
    const double u = den == 0.0 ? 0.0 : std::clamp(slicer::cross(a - p0, d) / den, 0.0, 1.0);
    const double s =
        rs.s_mm[static_cast<std::size_t>(r)][static_cast<std::size_t>(i)] + u * e.norm();
    cuts.push_back({t, {r, i, s}, p0 + t * d});
  });
  std::sort(cuts.begin(), cuts.end(), [](const Cut& x, const Cut& y) {
    return x.t != y.t ? x.t < y.t
                      : std::make_pair(x.spot.ring, x.spot.edge) <
                            std::make_pair(y.spot.ring, y.spot.edge);
  });
  return cuts;
}

// Even-odd inside test of p with the same predicate: count cuts of a segment from a point
// certainly outside (left of every ring) to p.
bool inside(const RingSet& rs, const Vec2& p, double left_x) {
  const Vec2 far(left_x, p.y() + 0.5);  // slanted so it rarely runs along an edge
  int n = 0;
  for (const auto& ring : rs.rings) {
    for (std::size_t i = 0; i < ring.size(); ++i)
      n += crosses(far, p, ring[i], ring[(i + 1) % ring.size()]);
  }
  return n % 2 == 1;
}

}  // namespace

RingSet ring_set(const std::vector<slicer::Ring>& rings) {
  RingSet rs;
  for (const auto& ring : rings) {
    if (ring.size() < 3) continue;
    std::vector<double> s{0.0};
    for (std::size_t i = 0; i < ring.size(); ++i)
      s.push_back(s.back() + (ring[(i + 1) % ring.size()] - ring[i]).norm());
    rs.rings.push_back(ring);
    rs.s_mm.push_back(std::move(s));
  }
  return rs;
}

double ring_length_mm(const RingSet& rs, int ring) {
  return rs.s_mm[static_cast<std::size_t>(ring)].back();
}

Vec2 point_at(const RingSet& rs, const RingSpot& spot) {
  const auto& ring = rs.rings[static_cast<std::size_t>(spot.ring)];
  const auto& s = rs.s_mm[static_cast<std::size_t>(spot.ring)];
  const std::size_t i = static_cast<std::size_t>(spot.edge);
  const Vec2& a = ring[i];
  const Vec2& b = ring[(i + 1) % ring.size()];
  const double len = s[i + 1] - s[i];
  return len > 0.0 ? Vec2(a + (b - a) * std::clamp((spot.s_mm - s[i]) / len, 0.0, 1.0)) : a;
}

double ring_gap(const RingSet& rs, const RingSpot& a, const RingSpot& b) {
  const double len = ring_length_mm(rs, a.ring);
  double d = b.s_mm - a.s_mm;
  if (d < 0.0) d += len;
  return d;
}

void walk_ring(const RingSet& rs, const RingSpot& a, const RingSpot& b, bool forward,
               std::vector<Vec2>& out) {
  const auto& ring = rs.rings[static_cast<std::size_t>(a.ring)];
  const int n = static_cast<int>(ring.size());
  const double gap = forward ? ring_gap(rs, a, b) : ring_gap(rs, b, a);
  if (gap > 0.0) {
    // Vertex indices passed: forward from a.edge + 1 to b.edge; backward from a.edge to b.edge + 1.
    int i = forward ? (a.edge + 1) % n : a.edge;
    // Walking backward along edge b.edge from its end vertex b.edge + 1 reaches b first.
    const int stop = forward ? b.edge : (b.edge + 1) % n;
    const bool same_edge_ahead =
        forward ? (a.edge == b.edge && a.s_mm <= b.s_mm) : (a.edge == b.edge && a.s_mm >= b.s_mm);
    if (!same_edge_ahead) {
      for (int k = 0; k <= n; ++k) {
        out.push_back(ring[static_cast<std::size_t>(i)]);
        if (i == stop) break;
        i = forward ? (i + 1) % n : (i - 1 + n) % n;
      }
    }
  }
  out.push_back(point_at(rs, b));
}

std::vector<FillPiece> clip_to_rings(const RingSet& rs, const std::vector<PatternLine>& lines) {
  std::vector<FillPiece> out;
  if (rs.rings.empty()) return out;
  EdgeGrid grid(rs);
  double left_x = 0.0;
  for (const auto& ring : rs.rings) {
    for (const Vec2& v : ring) left_x = std::min(left_x, v.x());
  }
  left_x -= 1.0;
  for (const PatternLine& line : lines) {
    if (line.points.size() < 2) continue;
    bool in = inside(rs, line.points.front(), left_x);
    FillPiece cur;
    cur.line.order = line.order;
    if (in) cur.line.points.push_back(line.points.front());
    for (std::size_t i = 0; i + 1 < line.points.size(); ++i) {
      const Vec2 &p0 = line.points[i], &p1 = line.points[i + 1];
      for (const Cut& c : cuts_of(rs, grid, p0, p1)) {
        if (in) {
          cur.line.points.push_back(c.at);
          cur.line.features.push_back(line.features[i]);
          cur.end = c.spot;
          out.push_back(cur);
          cur = FillPiece{};
          cur.line.order = line.order;
        } else {
          cur.start = c.spot;
          cur.line.points.push_back(c.at);
        }
        in = !in;
      }
      if (in) {
        cur.line.points.push_back(p1);
        cur.line.features.push_back(line.features[i]);
      }
    }
    if (in && cur.line.points.size() >= 2) out.push_back(cur);  // ends inside: open end
  }
  return out;
}

}  // namespace strand::patterns
