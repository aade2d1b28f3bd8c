// Triangle-soup slicing: plane cuts of every triangle, chained by exact end points, small
// gaps closed on a grid of loose ends, then Clipper's nonzero union (region.h).
#include "slicer/mesh_slicer.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <tuple>
#include <unordered_map>

#include "slicer/tolerances.h"

namespace strand::slicer {

ContourStats& ContourStats::operator+=(const ContourStats& o) {
  gaps_closed += o.gaps_closed;
  widest_gap_mm = std::max(widest_gap_mm, o.widest_gap_mm);
  wide_gaps_closed += o.wide_gaps_closed;
  reversed_segments += o.reversed_segments;
  dropped_pieces += o.dropped_pieces;
  return *this;
}

namespace {

struct Segment {
  Vec2 from, to;
};

bool lex_less(const Vec3& a, const Vec3& b) {
  return std::tie(a.x(), a.y(), a.z()) < std::tie(b.x(), b.y(), b.z());
}

// Where the edge a-b meets the plane: computed from the edge's lexicographically first end so
// both triangles on an edge (or on coincident edges of different shells) get the same bits.
Vec2 edge_point(Vec3 a, Vec3 b, double z) {
  if (lex_less(b, a)) std::swap(a, b);
  const double t = (z - a.z()) / (b.z() - a.z());
  const Vec2 p(a.x() + t * (b.x() - a.x()), a.y() + t * (b.y() - a.y()));
  return Vec2(p.x() + 0.0, p.y() + 0.0);  // -0 becomes +0: one key per point
}

// The cut of triangle t by the plane (no vertex lies on it), solid on the left for a
// counter-clockwise outward triangle: from the edge that goes down to the edge that goes up.
bool cut_triangle(const Mesh& m, const std::array<int, 3>& t, double z, Segment& out) {
  const Vec3* p[3] = {&m.vertices_mm[static_cast<std::size_t>(t[0])],
                      &m.vertices_mm[static_cast<std::size_t>(t[1])],
                      &m.vertices_mm[static_cast<std::size_t>(t[2])]};
  bool above[3];
  for (int k = 0; k < 3; ++k) above[k] = p[k]->z() > z;
  if (above[0] == above[1] && above[1] == above[2]) return false;
  bool have_down = false, have_up = false;
  for (int k = 0; k < 3; ++k) {
    const int n = (k + 1) % 3;
    if (above[k] == above[n]) continue;
    const Vec2 q = edge_point(*p[k], *p[n], z);
    if (above[k]) {
      out.from = q;
      have_down = true;
    } else {
      out.to = q;
      have_up = true;
    }
  }
  return have_down && have_up && out.from != out.to;
}

struct PointKey {
  std::uint64_t x, y;
  bool operator==(const PointKey&) const = default;
};
struct PointKeyHash {
  std::size_t operator()(const PointKey& k) const {
    return static_cast<std::size_t>(k.x * 0x9E3779B97F4A7C15ull ^ (k.y + 0x632BE59BD9B4E019ull));
  }
};

PointKey key_of(const Vec2& p) {
  PointKey k{};
  std::memcpy(&k.x, &p.x(), sizeof k.x);
  std::memcpy(&k.y, &p.y(), sizeof k.y);
  return k;
}

using Chain = std::vector<Vec2>;

// Segments into chains through exactly shared end points; a chain that cannot go on forward
// follows a segment that ends where it stands backwards (a flipped triangle).
void chain_exact(const std::vector<Segment>& segs, std::vector<Chain>& closed,
                 std::vector<Chain>& open, ContourStats& stats) {
  std::unordered_map<PointKey, int, PointKeyHash> ids;
  ids.reserve(segs.size() * 2);
  std::vector<int> from(segs.size()), to(segs.size());
  auto id_of = [&](const Vec2& p) {
    return ids.emplace(key_of(p), static_cast<int>(ids.size())).first->second;
  };
  for (std::size_t i = 0; i < segs.size(); ++i) {
    from[i] = id_of(segs[i].from);
    to[i] = id_of(segs[i].to);
  }
  // Outgoing and incoming segments per point, in segment order (CSR).
  const std::size_t n_points = ids.size();
  std::vector<int> out_start(n_points + 1, 0), in_start(n_points + 1, 0);
  for (std::size_t i = 0; i < segs.size(); ++i) {
    ++out_start[static_cast<std::size_t>(from[i]) + 1];
    ++in_start[static_cast<std::size_t>(to[i]) + 1];
  }
  for (std::size_t k = 0; k < n_points; ++k) {
    out_start[k + 1] += out_start[k];
    in_start[k + 1] += in_start[k];
  }
  std::vector<int> out_list(segs.size()), in_list(segs.size());
  {
    std::vector<int> oc(out_start.begin(), out_start.end() - 1),
        ic(in_start.begin(), in_start.end() - 1);
    for (std::size_t i = 0; i < segs.size(); ++i) {
      out_list[static_cast<std::size_t>(oc[static_cast<std::size_t>(from[i])]++)] =
          static_cast<int>(i);
      in_list[static_cast<std::size_t>(ic[static_cast<std::size_t>(to[i])]++)] =
          static_cast<int>(i);
    }
  }
  std::vector<int> out_cursor(out_start.begin(), out_start.end() - 1),
      in_cursor(in_start.begin(), in_start.end() - 1);
  std::vector<char> used(segs.size(), 0);
  auto next_unused = [&](std::vector<int>& cursor, const std::vector<int>& start,
                         const std::vector<int>& list, int point) {
    const auto p = static_cast<std::size_t>(point);
    while (cursor[p] < start[p + 1] &&
           used[static_cast<std::size_t>(list[static_cast<std::size_t>(cursor[p])])])
      ++cursor[p];
    return cursor[p] < start[p + 1] ? list[static_cast<std::size_t>(cursor[p])] : -1;
  };
  for (std::size_t s = 0; s < segs.size(); ++s) {
    if (used[s]) continue;
    Chain c{segs[s].from};
    const int first = from[s];
    int seg = static_cast<int>(s);
    bool backwards = false, is_closed = false;
    while (true) {
      const auto u = static_cast<std::size_t>(seg);
      used[u] = 1;
      const int at = backwards ? from[u] : to[u];
      c.push_back(backwards ? segs[u].from : segs[u].to);
      if (at == first) {
        is_closed = true;
        break;
      }
      seg = next_unused(out_cursor, out_start, out_list, at);
      backwards = false;
      if (seg < 0) {
        seg = next_unused(in_cursor, in_start, in_list, at);
        backwards = true;
        if (seg < 0) break;
        ++stats.reversed_segments;
      }
    }
    if (is_closed) {
      c.pop_back();
      closed.push_back(std::move(c));
    } else {
      open.push_back(std::move(c));
    }
  }
}

// Open chains joined end to start, nearest pairs first, within kMaxContourGapMm; what stays
// open is closed across its own gap when it has 3 points or more, dropped otherwise.
void close_gaps(std::vector<Chain> open, std::vector<Chain>& closed, ContourStats& stats) {
  if (open.empty()) return;
  const double cell = kMaxContourGapMm;
  auto cell_of = [&](const Vec2& p) {
    // Clamped before the cast: a far coordinate must not overflow (UB found by mesh_fuzz).
    const auto index = [&](double v) {
      return static_cast<std::int64_t>(std::clamp(std::floor(v / cell), -1e15, 1e15));
    };
    return std::pair<std::int64_t, std::int64_t>(index(p.x()), index(p.y()));
  };
  struct CellHash {
    std::size_t operator()(const std::pair<std::int64_t, std::int64_t>& c) const {
      return static_cast<std::size_t>(static_cast<std::uint64_t>(c.first) * 0x9E3779B97F4A7C15ull ^
                                      static_cast<std::uint64_t>(c.second));
    }
  };
  std::unordered_map<std::pair<std::int64_t, std::int64_t>, std::vector<int>, CellHash> starts;
  for (std::size_t j = 0; j < open.size(); ++j) {
    starts[cell_of(open[j].front())].push_back(static_cast<int>(j));
  }
  std::vector<std::tuple<double, int, int>> pairs;  // gap, end of chain i, start of chain j
  for (std::size_t i = 0; i < open.size(); ++i) {
    const Vec2& e = open[i].back();
    const auto [cx, cy] = cell_of(e);
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        const auto it = starts.find({cx + dx, cy + dy});
        if (it == starts.end()) continue;
        for (const int j : it->second) {
          const double d = (open[static_cast<std::size_t>(j)].front() - e).norm();
          if (d <= kMaxContourGapMm) pairs.emplace_back(d, static_cast<int>(i), j);
        }
      }
    }
  }
  std::sort(pairs.begin(), pairs.end());
  std::vector<int> next(open.size(), -1), prev(open.size(), -1);
  for (const auto& [d, i, j] : pairs) {
    if (next[static_cast<std::size_t>(i)] >= 0 || prev[static_cast<std::size_t>(j)] >= 0) continue;
    next[static_cast<std::size_t>(i)] = j;
    prev[static_cast<std::size_t>(j)] = i;
    if (d > 0.0) {
      ++stats.gaps_closed;
      stats.widest_gap_mm = std::max(stats.widest_gap_mm, d);
    }
  }
  std::vector<char> done(open.size(), 0);
  auto walk = [&](std::size_t from_chain) {
    Chain c;
    for (int k = static_cast<int>(from_chain); k >= 0 && !done[static_cast<std::size_t>(k)];
         k = next[static_cast<std::size_t>(k)]) {
      done[static_cast<std::size_t>(k)] = 1;
      const Chain& piece = open[static_cast<std::size_t>(k)];
      const bool joined = !c.empty() && c.back() == piece.front();
      c.insert(c.end(), piece.begin() + (joined ? 1 : 0), piece.end());
    }
    if (c.size() > 1 && c.front() == c.back()) c.pop_back();
    return c;
  };
  for (std::size_t i = 0; i < open.size(); ++i) {  // paths: chains nothing leads into
    if (done[i] || prev[i] >= 0) continue;
    Chain c = walk(i);
    if (c.size() < 3) {
      ++stats.dropped_pieces;
      continue;
    }
    ++stats.wide_gaps_closed;
    closed.push_back(std::move(c));
  }
  for (std::size_t i = 0; i < open.size(); ++i) {  // the rest are cycles of chains
    if (done[i]) continue;
    Chain c = walk(i);
    if (c.size() >= 3) closed.push_back(std::move(c));
  }
}

double nudged(const std::vector<double>& vertex_z, double z) {
  while (std::binary_search(vertex_z.begin(), vertex_z.end(), z)) z += kSliceNudgeMm;
  return z;
}

std::vector<Ring> loops_of(const std::vector<Segment>& segs, ContourStats& stats) {
  std::vector<Chain> closed, open;
  chain_exact(segs, closed, open, stats);
  close_gaps(std::move(open), closed, stats);
  std::vector<Ring> out;
  out.reserve(closed.size());
  for (Chain& c : closed) {
    if (c.size() >= 3) out.push_back(std::move(c));
  }
  return out;
}

}  // namespace

MeshSlicer::MeshSlicer(const Mesh& m) : mesh_(m) {
  vertex_z_.reserve(m.vertices_mm.size());
  for (const Vec3& v : m.vertices_mm) vertex_z_.push_back(v.z());
  std::sort(vertex_z_.begin(), vertex_z_.end());
}

std::vector<Ring> slice_at(const MeshSlicer& s, double z_mm, ContourStats* stats) {
  const double z = nudged(s.vertex_z(), z_mm);
  std::vector<Segment> segs;
  Segment seg;
  for (const auto& t : s.mesh().triangles) {
    if (cut_triangle(s.mesh(), t, z, seg)) segs.push_back(seg);
  }
  ContourStats local;
  std::vector<Ring> out = loops_of(segs, local);
  if (stats) *stats += local;
  return out;
}

LayerCuts::LayerCuts(const Mesh& m, double layer_height_mm, int layers) : slicer_(m) {
  // Triangles by their lowest z; a sweep keeps those the plane can still meet.
  std::vector<std::pair<double, double>> span(m.triangles.size());
  std::vector<int> order(m.triangles.size());
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    double lo = m.vertices_mm[static_cast<std::size_t>(m.triangles[t][0])].z(), hi = lo;
    for (int k = 1; k < 3; ++k) {
      const double z = m.vertices_mm[static_cast<std::size_t>(m.triangles[t][k])].z();
      lo = std::min(lo, z);
      hi = std::max(hi, z);
    }
    span[t] = {lo, hi};
    order[t] = static_cast<int>(t);
  }
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return span[static_cast<std::size_t>(a)].first < span[static_cast<std::size_t>(b)].first;
  });
  std::vector<int> active;
  std::size_t next = 0;
  const std::size_t n = static_cast<std::size_t>(std::max(layers, 0));
  z_mm_.reserve(n);
  active_.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double z = nudged(slicer_.vertex_z(), (static_cast<double>(k) + 0.5) * layer_height_mm);
    while (next < order.size() && span[static_cast<std::size_t>(order[next])].first < z) {
      active.push_back(order[next++]);
    }
    std::erase_if(active, [&](int t) { return span[static_cast<std::size_t>(t)].second < z; });
    std::sort(active.begin(), active.end());  // triangle order: the same loops every run
    z_mm_.push_back(z);
    active_.push_back(active);
  }
}

Region LayerCuts::cut(int k, ContourStats& stats) const {
  const std::size_t i = static_cast<std::size_t>(k);
  const Mesh& m = slicer_.mesh();
  std::vector<Segment> segs;
  Segment seg;
  for (const int t : active_.at(i)) {
    if (cut_triangle(m, m.triangles[static_cast<std::size_t>(t)], z_mm_[i], seg)) segs.push_back(seg);
  }
  return region_from_oriented_loops(loops_of(segs, stats));
}

std::vector<Region> slice_layers(const Mesh& m, double layer_height_mm, int layers,
                                 ContourStats* stats) {
  const LayerCuts cuts(m, layer_height_mm, layers);
  std::vector<Region> out;
  out.reserve(static_cast<std::size_t>(cuts.layers()));
  ContourStats total;
  for (int k = 0; k < cuts.layers(); ++k) out.push_back(cuts.cut(k, total));
  if (stats) *stats += total;
  return out;
}

}  // namespace strand::slicer
