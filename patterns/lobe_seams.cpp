// Cells of a scaffold layer's chords and a slit down the middle of each (patterns/lobe_seams.h).
#include "patterns/lobe_seams.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace strand::patterns {

using slicer::Vec2;

namespace {

struct Chord {
  double a = 0.0, b = 0.0;  // extent along the lines
  double t = 0.0;           // across the lines
  int row = 0;
  std::vector<std::size_t> up, down;  // overlapping chords in rows row - 1 and row + 1
};

bool overlap(const Chord& p, const Chord& q) {
  return std::min(p.b, q.b) - std::max(p.a, q.a) > 0.0;
}

// A chain continues from chord i to j: i's only neighbour below is j and j's only one above is i.
bool continues(const std::vector<Chord>& c, std::size_t i) {
  return c[i].down.size() == 1 && c[c[i].down[0]].up.size() == 1;
}

// Per pair of dead-end cells (the first `dead` of `cells`), the cells off the path between
// them through the cells' adjacency (as `out_of` numbers them; cells it leaves out have no
// cut), longest path first; at most kMaxSpines, of the first 16 dead ends.
std::vector<std::vector<std::size_t>> spines(const std::vector<Chord>& chords,
                                             const std::vector<std::vector<std::size_t>>& cells,
                                             std::size_t dead,
                                             const std::vector<std::size_t>& out_of) {
  constexpr std::size_t kMaxSpines = 24;
  const std::size_t n = cells.size();
  std::vector<std::size_t> cell_of(chords.size(), n);
  for (std::size_t c = 0; c < n; ++c) {
    for (const std::size_t i : cells[c]) cell_of[i] = c;
  }
  std::vector<std::vector<std::size_t>> adj(n);
  for (std::size_t c = 0; c < n; ++c) {
    for (const std::size_t i : chords[cells[c].back()].down) {
      const std::size_t d = cell_of[i];
      if (d == c || d == n) continue;
      adj[c].push_back(d);
      adj[d].push_back(c);
    }
  }
  for (auto& a : adj) {
    std::sort(a.begin(), a.end());
    a.erase(std::unique(a.begin(), a.end()), a.end());
  }
  // Breadth-first from `from`: each cell's predecessor (n: unreached).
  const auto tree = [&](std::size_t from) {
    std::vector<std::size_t> pred(n, n);
    std::vector<std::size_t> queue{from};
    pred[from] = from;
    for (std::size_t q = 0; q < queue.size(); ++q) {
      for (const std::size_t d : adj[queue[q]]) {
        if (pred[d] == n) pred[d] = queue[q], queue.push_back(d);
      }
    }
    return pred;
  };
  struct Spine {
    std::size_t length;
    std::vector<std::size_t> off;
  };
  std::vector<Spine> found;
  const std::size_t ends = std::min<std::size_t>(dead, 16);
  for (std::size_t a = 0; a < ends; ++a) {
    const std::vector<std::size_t> pred = tree(a);
    for (std::size_t b = a + 1; b < ends; ++b) {
      if (pred[b] == n) continue;
      std::vector<bool> on(n, false);
      std::size_t length = 1;
      for (std::size_t c = b; c != a; c = pred[c]) on[c] = true, ++length;
      on[a] = true;
      Spine spine{length, {}};
      for (std::size_t c = 0; c < n; ++c) {
        if (!on[c] && out_of[c] < n) spine.off.push_back(out_of[c]);
      }
      std::sort(spine.off.begin(), spine.off.end());
      found.push_back(std::move(spine));
    }
  }
  std::stable_sort(found.begin(), found.end(),
                   [](const Spine& x, const Spine& y) { return x.length > y.length; });
  std::vector<std::vector<std::size_t>> out;
  for (auto& spine : found) {
    if (out.size() == kMaxSpines) break;
    if (std::find(out.begin(), out.end(), spine.off) == out.end())
      out.push_back(std::move(spine.off));
  }
  return out;
}

}  // namespace

LobeSeams lobe_seams(const slicer::Region& fill, const std::vector<FillPiece>& pieces,
                     const SeamOptions& o) {
  LobeSeams out;
  const bool lines = std::all_of(pieces.begin(), pieces.end(), [](const FillPiece& piece) {
    return piece.line.points.size() >= 2;
  });
  if (pieces.empty() || !lines || o.pitch_mm <= 0.0 || o.nozzle_mm <= 0.0) return out;
  // The lines' direction u (all pieces parallel and straight) and the across direction n.
  Vec2 u = pieces.front().line.points.back() - pieces.front().line.points.front();
  if (u.norm() <= 0.0) return out;
  u.normalize();
  if (u.x() < 0.0 || (u.x() == 0.0 && u.y() < 0.0)) u = -u;
  const Vec2 n(-u.y(), u.x());
  std::vector<Chord> chords;
  for (const FillPiece& piece : pieces) {
    const Vec2 &p = piece.line.points.front(), &q = piece.line.points.back();
    for (const Vec2& v : piece.line.points) {
      if (std::abs((v - p).dot(n)) > 1e-6) return out;  // not a straight chord along u
    }
    Chord c;
    c.a = std::min(p.dot(u), q.dot(u));
    c.b = std::max(p.dot(u), q.dot(u));
    c.t = p.dot(n);
    c.row = piece.line.order;
    chords.push_back(c);
  }
  std::map<int, std::vector<std::size_t>> rows;
  for (std::size_t i = 0; i < chords.size(); ++i) rows[chords[i].row].push_back(i);
  for (auto& [row, members] : rows) {
    const auto below = rows.find(row + 1);
    if (below == rows.end()) continue;
    for (const std::size_t i : members) {
      for (const std::size_t j : below->second) {
        if (!overlap(chords[i], chords[j])) continue;
        chords[i].down.push_back(j);
        chords[j].up.push_back(i);
      }
    }
  }
  // Cells: maximal chains, each started at a chord no chain continues into.
  std::vector<std::vector<std::size_t>> cells;
  for (const auto& [row, members] : rows) {
    for (const std::size_t i : members) {
      if (chords[i].up.size() == 1 && continues(chords, chords[i].up[0])) continue;
      std::vector<std::size_t> cell{i};
      while (continues(chords, cell.back())) cell.push_back(chords[cell.back()].down[0]);
      cells.push_back(std::move(cell));
    }
  }
  const auto dead_end = [&](const std::vector<std::size_t>& cell) {
    return chords[cell.front()].up.empty() || chords[cell.back()].down.empty();
  };
  const auto first_inner = std::stable_partition(cells.begin(), cells.end(), dead_end);

  // A cut chord keeps min_half on each side of a slit at least one nozzle wide; the slit
  // is one gap wide (the two beads along it a pitch apart) where the lobe allows.
  const double need = o.nozzle_mm + 2.0 * o.min_half_mm;
  // Slits stay inside the fill ring by half a nozzle (the beads along the slit and the ring
  // overlap by half at most), or by a tenth where a lobe's tip comes so close to its last
  // chord that only then is that chord cut.
  const slicer::Region inside = slicer::offset_region(fill, -0.5 * o.nozzle_mm);
  const slicer::Region inside_tip = slicer::offset_region(fill, -0.1 * o.nozzle_mm);
  // The slit through chords cell[i0..i1], from half a row before the first to half a row
  // after the last, `width` wide, kept inside `within`.
  const auto slit = [&](const std::vector<std::size_t>& cell, std::size_t i0, std::size_t i1,
                        double width, const slicer::Region& within) {
    const double dir =
        i1 > i0 ? (chords[cell[i1]].t > chords[cell[i0]].t ? 1.0 : -1.0)
                : (cell.size() > 1 && chords[cell[1]].t < chords[cell[0]].t ? -1.0 : 1.0);
    std::vector<Vec2> mid;  // (along, across) of the slit's centre line
    const auto centre = [&](std::size_t k) {
      return 0.5 * (chords[cell[k]].a + chords[cell[k]].b);
    };
    mid.emplace_back(centre(i0), chords[cell[i0]].t - dir * 0.5 * o.pitch_mm);
    for (std::size_t k = i0; k <= i1; ++k) mid.emplace_back(centre(k), chords[cell[k]].t);
    mid.emplace_back(centre(i1), chords[cell[i1]].t + dir * 0.5 * o.pitch_mm);
    slicer::Ring ring;
    for (const Vec2& m : mid) ring.push_back((m.x() - width / 2) * u + m.y() * n);
    for (auto m = mid.rbegin(); m != mid.rend(); ++m)
      ring.push_back((m->x() + width / 2) * u + m->y() * n);
    return slicer::region_intersection(slicer::region_from_contours({ring}), within);
  };
  // Where a cell's chords are left out: a strip a half pitch wide along each of them.
  const auto drop = [&](const std::vector<std::size_t>& cell) {
    std::vector<slicer::Ring> strips;
    for (const std::size_t i : cell) {
      const Chord& c = chords[i];
      const double w = 0.25 * o.pitch_mm;
      strips.push_back({c.a * u + (c.t - w) * n, c.b * u + (c.t - w) * n, c.b * u + (c.t + w) * n,
                        c.a * u + (c.t + w) * n});
    }
    return CellCut{slicer::region_from_oriented_loops(strips), true};
  };
  // A cell whose chords may be left out: none longer than a pitch, so the beads along its
  // two sides leave no wider a gap than the pattern's own.
  const auto narrow = [&](const std::vector<std::size_t>& cell) {
    return std::all_of(cell.begin(), cell.end(),
                       [&](std::size_t i) { return chords[i].b - chords[i].a <= o.pitch_mm; });
  };
  std::vector<std::size_t> out_of(cells.size(), cells.size());  // cell -> out.cells index
  for (auto cell_it = cells.begin(); cell_it != cells.end(); ++cell_it) {
    const auto& cell = *cell_it;
    // The longest run of chords long enough to cut.
    std::size_t best0 = 0, best_len = 0;
    for (std::size_t i = 0; i < cell.size();) {
      std::size_t j = i;
      while (j < cell.size() && chords[cell[j]].b - chords[cell[j]].a >= need) ++j;
      if (j - i > best_len) best0 = i, best_len = j - i;
      i = j + 1;
    }
    if (best_len == 0) {  // too narrow to halve: the cell's chords are left out instead
      if (!narrow(cell)) continue;
      out_of[static_cast<std::size_t>(cell_it - cells.begin())] = out.cells.size();
      out.cells.push_back({drop(cell), drop(cell)});
      if (cell_it < first_inner) out.dead_ends = out.cells.size();
      continue;
    }
    const std::size_t i0 = best0, i1 = best0 + best_len - 1;
    double shortest = chords[cell[i0]].b - chords[cell[i0]].a;
    for (std::size_t k = i0; k <= i1; ++k)
      shortest = std::min(shortest, chords[cell[k]].b - chords[cell[k]].a);
    // The shortest chord's halves a little over min_half, so rounding keeps them.
    const double width = std::clamp(shortest - 2.0 * o.min_half_mm - 0.1 * o.nozzle_mm, o.nozzle_mm,
                                    std::max(o.nozzle_mm, o.pitch_mm - o.nozzle_mm));
    std::vector<CellCut> variants;
    const auto add = [&](std::size_t a, std::size_t b, const slicer::Region& within) {
      slicer::Region r = slit(cell, a, b, width, within);
      if (!r.empty()) variants.push_back({std::move(r), false});
    };
    // Every chord (a half shorter than min_half is left out; the lobe is still entered and
    // left beside its first chord, whatever the parity), close to the tip or not; then the
    // long ones, then those with the first or last left whole.
    add(0, cell.size() - 1, inside_tip);
    if (variants.empty()) continue;
    add(0, cell.size() - 1, inside);
    if (variants.size() < 2) variants.push_back(variants.front());  // variant 1 always there
    if (i0 > 0 || i1 + 1 < cell.size()) add(i0, i1, inside);
    if (i1 > i0) {
      add(i0 + 1, i1, inside);
      add(i0, i1 - 1, inside);
    }
    if (i1 > i0 + 1) add(i0 + 1, i1 - 1, inside);
    if (narrow(cell)) variants.push_back(drop(cell));
    out_of[static_cast<std::size_t>(cell_it - cells.begin())] = out.cells.size();
    out.cells.push_back(std::move(variants));
    if (cell_it < first_inner) out.dead_ends = out.cells.size();
  }
  out.spines = spines(chords, cells, static_cast<std::size_t>(first_inner - cells.begin()), out_of);
  return out;
}

bool round_lobe(const RingSet& rs, const slicer::Region& drop, std::vector<FillPiece>& pieces) {
  std::vector<std::size_t> in;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const auto& pts = pieces[i].line.points;
    if (!pts.empty() && slicer::contains(drop, (pts.front() + pts.back()) / 2.0)) in.push_back(i);
  }
  if (in.empty()) return false;
  const int ring = pieces[in.front()].start.ring;
  if (ring < 0) return false;
  std::vector<RingSpot> spots;
  for (const std::size_t i : in) {
    for (const RingSpot& e : {pieces[i].start, pieces[i].end}) {
      if (e.ring != ring) return false;
      spots.push_back(e);
    }
  }
  std::sort(spots.begin(), spots.end(),
            [](const RingSpot& a, const RingSpot& b) { return a.s_mm < b.s_mm; });
  // The arc round the lobe leaves out one gap between consecutive ends: the one holding every
  // other piece's end on this ring, or else the longest.
  std::size_t gap = spots.size();  // the gap after spots[gap]
  double longest = -1.0;
  for (std::size_t k = 0; k < spots.size(); ++k) {
    const RingSpot &a = spots[k], &b = spots[(k + 1) % spots.size()];
    const double width = ring_gap(rs, a, b);
    bool holds_all = true;
    for (std::size_t i = 0, j = 0; i < pieces.size() && holds_all; ++i) {
      if (j < in.size() && in[j] == i) {
        ++j;
        continue;
      }
      for (const RingSpot& e : {pieces[i].start, pieces[i].end}) {
        holds_all = holds_all &&
                    (e.ring != ring || (ring_gap(rs, a, e) > 0.0 && ring_gap(rs, a, e) < width));
      }
    }
    if (holds_all && width > longest) gap = k, longest = width;
  }
  if (gap == spots.size()) return false;
  const RingSpot from = spots[(gap + 1) % spots.size()], to = spots[gap];
  FillPiece lobe;
  lobe.start = from;
  lobe.end = to;
  lobe.line.order = pieces[in.front()].line.order;
  const slicer::Feature feature = pieces[in.front()].line.features.empty()
                                      ? slicer::Feature::Infill
                                      : pieces[in.front()].line.features.front();
  lobe.line.points.push_back(point_at(rs, from));
  walk_ring(rs, from, to, true, lobe.line.points);
  lobe.line.features.assign(lobe.line.points.size() - 1, feature);
  const std::size_t at = in.front();
  for (std::size_t k = in.size(); k-- > 0;)
    pieces.erase(pieces.begin() + static_cast<std::ptrdiff_t>(in[k]));
  pieces.insert(pieces.begin() + static_cast<std::ptrdiff_t>(at), std::move(lobe));
  return true;
}

}  // namespace strand::patterns
