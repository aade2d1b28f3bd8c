// Per-layer contact search on a uniform grid sized to the segment count.
#include "postprocess/crossings.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "postprocess/arc_segmentation.h"

namespace strand::post {

using slicer::Vec2;

namespace {

struct Seg {
  Vec2 a, b;
  std::size_t move;  // source move
  long strand;       // strand id within the program
  long index;        // position within its strand (consecutive pieces differ by 1)
};

struct LayerSegs {
  int layer;
  std::vector<Seg> segs;
};

// Flattens deposits into per-layer segment lists with strand ids.
std::vector<LayerSegs> collect(const slicer::MotionProgram& p, double tol) {
  std::vector<LayerSegs> out;
  slicer::Vec3 at = p.start_mm;
  long strand = -1, index = 0;
  bool depositing = false;
  int layer = -2;
  for (std::size_t i = 0; i < p.moves.size(); ++i) {
    const auto& mv = p.moves[i];
    if (mv.kind == slicer::MoveKind::Raw || mv.kind == slicer::MoveKind::Dwell) continue;
    if (mv.layer != layer) {
      layer = mv.layer;
      depositing = false;
      out.push_back({layer, {}});
    }
    if (mv.kind != slicer::MoveKind::Deposit) {
      if ((mv.end_mm - at).norm() > 0) depositing = false;
      at = mv.end_mm;
      continue;
    }
    if (!depositing) ++strand, index = 0;
    depositing = true;
    Vec2 from = at.head<2>();
    if (mv.is_arc) {
      for (const Vec2& q : segment_arc(from, mv.center_mm, mv.end_mm.head<2>(), mv.ccw, tol)) {
        out.back().segs.push_back({from, q, i, strand, index++});
        from = q;
      }
    } else if ((mv.end_mm.head<2>() - from).norm() > 0) {
      out.back().segs.push_back({from, mv.end_mm.head<2>(), i, strand, index++});
    }
    at = mv.end_mm;
  }
  return out;
}

bool adjacent(const Seg& s, const Seg& t) {
  return s.strand == t.strand && std::abs(s.index - t.index) == 1;
}

void check_layer(const LayerSegs& L, double touch, ContactReport& out) {
  const auto& segs = L.segs;
  if (segs.size() < 2) return;
  Vec2 lo = segs[0].a, hi = segs[0].a;
  double total = 0;
  for (const auto& s : segs) {
    lo = lo.cwiseMin(s.a).cwiseMin(s.b);
    hi = hi.cwiseMax(s.a).cwiseMax(s.b);
    total += (s.b - s.a).norm();
  }
  const double n = static_cast<double>(segs.size());
  const Vec2 ext = (hi - lo).cwiseMax(Vec2(1e-9, 1e-9));
  // Cells about one mean segment long, but never more cells than ~4 per segment.
  const double cell = std::max({total / n, std::sqrt(ext.x() * ext.y() / (4 * n)), 1e-6});
  const long nx = static_cast<long>(ext.x() / cell) + 1;
  std::unordered_map<long long, std::vector<std::uint32_t>> grid;
  grid.reserve(segs.size() * 2);
  auto key = [nx](long cx, long cy) { return static_cast<long long>(cy) * (nx + 1) + cx; };
  auto cell_of = [&](double v, double origin) { return static_cast<long>(std::floor((v - origin) / cell)); };
  for (std::uint32_t k = 0; k < segs.size(); ++k) {
    const auto& s = segs[k];
    const long x0 = cell_of(std::min(s.a.x(), s.b.x()) - touch, lo.x()), x1 = cell_of(std::max(s.a.x(), s.b.x()) + touch, lo.x());
    const long y0 = cell_of(std::min(s.a.y(), s.b.y()) - touch, lo.y()), y1 = cell_of(std::max(s.a.y(), s.b.y()) + touch, lo.y());
    for (long cy = y0; cy <= y1; ++cy) {
      for (long cx = x0; cx <= x1; ++cx) grid[key(cx, cy)].push_back(k);
    }
  }
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  for (const auto& [k, ids] : grid) {
    for (std::size_t i = 0; i < ids.size(); ++i) {
      for (std::size_t j = i + 1; j < ids.size(); ++j) pairs.emplace_back(std::min(ids[i], ids[j]), std::max(ids[i], ids[j]));
    }
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  for (const auto& [i, j] : pairs) {
    const Seg& s = segs[i];
    const Seg& t = segs[j];
    if (adjacent(s, t)) continue;
    const auto c = slicer::segment_contact(s.a, s.b, t.a, t.b, touch);
    if (c == slicer::Contact::Crossing) {
      out.crossings.push_back({L.layer, slicer::crossing_point(s.a, s.b, t.a, t.b), s.move, t.move});
    } else if (c == slicer::Contact::Touch) {
      // A joint between consecutive moves split into chords is not a touch.
      if (s.move == t.move) continue;
      Vec2 at = (s.a - t.a).norm() <= touch || (s.a - t.b).norm() <= touch ? s.a : s.b;
      if (slicer::point_segment_distance(t.a, s.a, s.b) <= touch) at = t.a;
      else if (slicer::point_segment_distance(t.b, s.a, s.b) <= touch) at = t.b;
      out.touches.push_back({L.layer, at, s.move, t.move});
    }
  }
}

}  // namespace

ContactReport find_contacts(const slicer::MotionProgram& p, double tol, double touch) {
  ContactReport out;
  for (const auto& layer : collect(p, tol)) check_layer(layer, touch, out);
  auto by_move = [](const Contact& a, const Contact& b) {
    return std::tie(a.layer, a.move_a, a.move_b) < std::tie(b.layer, b.move_a, b.move_b);
  };
  std::sort(out.crossings.begin(), out.crossings.end(), by_move);
  std::sort(out.touches.begin(), out.touches.end(), by_move);
  return out;
}

}  // namespace strand::post
