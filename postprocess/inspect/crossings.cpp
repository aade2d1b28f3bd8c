// Per-layer contact search on a uniform grid: each segment is rasterised into the cells its
// touch-inflated body crosses (not its bounding box), so the work is linear in the total
// length over the cell size plus the pairs that really share a cell.
#include "postprocess/inspect/crossings.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "postprocess/plan/arc_segmentation.h"

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

// A grid over one layer's bounding box, cell size about one mean segment length.
struct Grid {
  Vec2 lo;
  double cell;
  std::int64_t nx;
  std::int64_t col(double x) const {
    return static_cast<std::int64_t>(std::floor((x - lo.x()) / cell));
  }
  std::int64_t row(double y) const {
    return static_cast<std::int64_t>(std::floor((y - lo.y()) / cell));
  }
  std::uint64_t key(std::int64_t cx, std::int64_t cy) const {
    return static_cast<std::uint64_t>((cy + 1) * (nx + 3) + (cx + 1));
  }
};

Grid make_grid(const std::vector<Seg>& segs) {
  Vec2 lo = segs[0].a, hi = segs[0].a;
  double total = 0;
  std::vector<double> lengths;
  lengths.reserve(segs.size());
  for (const auto& s : segs) {
    lo = lo.cwiseMin(s.a).cwiseMin(s.b);
    hi = hi.cwiseMax(s.a).cwiseMax(s.b);
    lengths.push_back((s.b - s.a).norm());
    total += lengths.back();
  }
  const auto mid = lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2);
  std::nth_element(lengths.begin(), mid, lengths.end());
  const double n = static_cast<double>(segs.size());
  const Vec2 ext = (hi - lo).cwiseMax(Vec2(1e-9, 1e-9));
  // Cells about one median segment long (a few long lines do not inflate the cells of a
  // dense node), but at most ~8n cells crossed in total, at most ~4n cells in the box, and
  // at most 2^20 cells along an axis (keys fit 64 bits for any coordinates).
  const double cell = std::max({*mid, total / (8 * n), std::sqrt(ext.x() * ext.y() / (4 * n)),
                                ext.maxCoeff() / double(1 << 20), 1e-6});
  return {lo, cell, static_cast<std::int64_t>(ext.x() / cell) + 1};
}

// Appends (cell key, segment) for every cell the segment, inflated by `pad`, may touch:
// column by column, the y-range the segment covers inside that column's slab.
void rasterise(const Grid& g, const Seg& s, std::uint32_t id, double pad,
               std::vector<std::pair<std::uint64_t, std::uint32_t>>& out) {
  const Vec2 p = s.a.x() <= s.b.x() ? s.a : s.b;
  const Vec2 q = s.a.x() <= s.b.x() ? s.b : s.a;
  const double dx = q.x() - p.x();
  const std::int64_t c0 = g.col(p.x() - pad), c1 = g.col(q.x() + pad);
  for (std::int64_t cx = c0; cx <= c1; ++cx) {
    const double x_lo = std::max(p.x(), g.lo.x() + static_cast<double>(cx) * g.cell - pad);
    const double x_hi = std::min(q.x(), g.lo.x() + static_cast<double>(cx + 1) * g.cell + pad);
    auto y_at = [&](double x) {
      return dx <= 0 ? p.y() : p.y() + (q.y() - p.y()) * (x - p.x()) / dx;
    };
    const double y_lo = dx <= 0 ? std::min(p.y(), q.y()) : std::min(y_at(x_lo), y_at(x_hi));
    const double y_hi = dx <= 0 ? std::max(p.y(), q.y()) : std::max(y_at(x_lo), y_at(x_hi));
    for (std::int64_t cy = g.row(y_lo - pad); cy <= g.row(y_hi + pad); ++cy)
      out.emplace_back(g.key(cx, cy), id);
  }
}

struct Found {
  std::uint32_t i, j;
  slicer::Contact kind;
  bool operator<(const Found& o) const { return std::tie(i, j) < std::tie(o.i, o.j); }
  bool operator==(const Found& o) const { return i == o.i && j == o.j; }
};

// Classifies one candidate pair; pairs sharing several cells are deduplicated later.
void test_pair(const std::vector<Seg>& segs, std::uint32_t i, std::uint32_t j, double touch,
               std::vector<Found>& found) {
  const Seg& s = segs[i];
  const Seg& t = segs[j];
  if (adjacent(s, t)) return;
  // Cheap reject: boxes apart by more than `touch` (most pairs sharing a cell).
  if (std::max(s.a.x(), s.b.x()) + touch < std::min(t.a.x(), t.b.x()) ||
      std::max(t.a.x(), t.b.x()) + touch < std::min(s.a.x(), s.b.x()) ||
      std::max(s.a.y(), s.b.y()) + touch < std::min(t.a.y(), t.b.y()) ||
      std::max(t.a.y(), t.b.y()) + touch < std::min(s.a.y(), s.b.y())) {
    return;
  }
  const auto c = slicer::segment_contact(s.a, s.b, t.a, t.b, touch);
  // A joint between consecutive moves split into chords is not a touch.
  if (c == slicer::Contact::None || (c == slicer::Contact::Touch && s.move == t.move)) return;
  found.push_back({std::min(i, j), std::max(i, j), c});
}

Vec2 touch_point(const Seg& s, const Seg& t, double touch) {
  if (slicer::point_segment_distance(t.a, s.a, s.b) <= touch) return t.a;
  if (slicer::point_segment_distance(t.b, s.a, s.b) <= touch) return t.b;
  return slicer::point_segment_distance(s.a, t.a, t.b) <= touch ? s.a : s.b;
}

void check_layer(const LayerSegs& L, double touch, ContactReport& out) {
  const auto& segs = L.segs;
  if (segs.size() < 2) return;
  const Grid g = make_grid(segs);
  std::vector<std::pair<std::uint64_t, std::uint32_t>> cells;
  cells.reserve(segs.size() * 3);
  for (std::uint32_t k = 0; k < segs.size(); ++k) rasterise(g, segs[k], k, touch, cells);
  std::sort(cells.begin(), cells.end());
  std::vector<Found> found;
  for (std::size_t b = 0; b < cells.size();) {
    std::size_t e = b + 1;
    while (e < cells.size() && cells[e].first == cells[b].first) ++e;
    for (std::size_t i = b; i < e; ++i) {
      for (std::size_t j = i + 1; j < e; ++j)
        test_pair(segs, cells[i].second, cells[j].second, touch, found);
    }
    b = e;
  }
  std::sort(found.begin(), found.end());
  found.erase(std::unique(found.begin(), found.end()), found.end());
  for (const Found& f : found) {
    const Seg& s = segs[f.i];
    const Seg& t = segs[f.j];
    if (f.kind == slicer::Contact::Crossing) {
      out.crossings.push_back(
          {L.layer, slicer::crossing_point(s.a, s.b, t.a, t.b), s.move, t.move});
    } else {
      out.touches.push_back({L.layer, touch_point(s, t, touch), s.move, t.move});
    }
  }
}

}  // namespace

ContactReport find_contacts(const slicer::MotionProgram& p, double tol, double touch) {
  ContactReport out;
  for (const auto& layer : collect(p, tol)) check_layer(layer, touch, out);
  auto by_move = [](const Contact& a, const Contact& b) {
    return std::tie(a.layer, a.move_a, a.move_b, a.at_mm.x(), a.at_mm.y()) <
           std::tie(b.layer, b.move_a, b.move_b, b.at_mm.x(), b.at_mm.y());
  };
  std::stable_sort(out.crossings.begin(), out.crossings.end(), by_move);
  std::stable_sort(out.touches.begin(), out.touches.end(), by_move);
  return out;
}

}  // namespace strand::post
