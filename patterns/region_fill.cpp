// Layer fills: wall check, perimeters, clipped and joined pattern, stroke order.
#include "patterns/region_fill.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>

#include "patterns/lobe_seams.h"
#include "patterns/neck_links.h"
#include "patterns/perimeter_splice.h"
#include "patterns/region_join.h"
#include "patterns/region_strands.h"
#include "slicer/input_error.h"

namespace strand::patterns {

using slicer::Region;
using slicer::Vec2;

namespace {

// The longest link across a neck (nozzles): ends on either side of a neck under three beads
// wide lie up to about three beads apart.
constexpr double kNeckReach = 3.0;

// Where a bead centred d/2 inside layer k's boundary cannot reach, over more than
// 4 nozzle^2, and the layers below and above cover that place too (a wall, not the thin
// rim at the top or bottom of a curved part): throws naming the place.
void check_wall(const std::vector<Region>& layers, std::size_t k, double nozzle_mm, double z_mm) {
  const double r = nozzle_mm / 2.0;
  const Region& region = layers[k];
  const Region reached = slicer::offset_region(slicer::offset_region(region, -r), r);
  for (const auto& lost : slicer::region_difference(region, reached)) {
    const double area = slicer::area_mm2(lost);
    if (area <= 4.0 * nozzle_mm * nozzle_mm) continue;
    bool wall = true;
    for (const std::size_t j : {k - 1, k + 1}) {  // k - 1 wraps for k = 0: not a layer
      wall = wall && j < layers.size() &&
             slicer::area_mm2(slicer::region_intersection({lost}, layers[j])) > area / 2;
    }
    if (!wall) continue;
    const auto [lo, hi] = slicer::region_bounds({lost});
    const Vec2 c = (lo + hi) / 2.0;
    char where[128];
    std::snprintf(where, sizeof where, "(%.3f, %.3f, %.3f)", c.x(), c.y(), z_mm);
    throw InputError("slice.nozzle = " + slicer::short_number(nozzle_mm) +
                     ": wider than the part's wall near " + where + " (a strip of " +
                     slicer::short_number(std::round(area * 10) / 10) +
                     " mm2 no bead can fill); use a finer nozzle or thicken the wall");
  }
}

slicer::Stroke ring_stroke(const slicer::Ring& ring, double width, double height) {
  slicer::Stroke s;
  s.start_mm = ring.front();
  for (std::size_t i = 1; i <= ring.size(); ++i)
    s.segments.push_back(slicer::line_to(ring[i % ring.size()], slicer::Feature::Wall));
  s.width_mm = width;
  s.height_mm = height;
  return s;
}

// A perimeter ring whose two sides lie under half a bead apart on average (twice its area over
// its length: the offset of a fin about a bead wide, there and back along one line) printed
// once, as the open line along one side from one end to the other, not as two beads on top of
// each other. The ends: the vertex farthest from the first, and the one farthest from that,
// at least a nozzle apart (a smaller ring, a dot in a corner, stays a loop).
std::optional<slicer::Stroke> flat_ring(const slicer::Ring& ring, double width, double height) {
  const std::size_t n = ring.size();
  if (n < 3) return std::nullopt;
  double length = 0.0;
  for (std::size_t i = 0; i < n; ++i) length += (ring[(i + 1) % n] - ring[i]).norm();
  if (length <= 0.0 || 2.0 * std::abs(slicer::signed_area_mm2(ring)) / length >= 0.5 * width)
    return std::nullopt;
  const auto farthest = [&](std::size_t from) {
    std::size_t best = from;
    for (std::size_t i = 0; i < n; ++i)
      if ((ring[i] - ring[from]).norm() > (ring[best] - ring[from]).norm()) best = i;
    return best;
  };
  const std::size_t i1 = farthest(0), i2 = farthest(i1);
  if ((ring[i2] - ring[i1]).norm() < width) return std::nullopt;  // a dot: a loop joins better
  slicer::Stroke s;
  s.start_mm = ring[i1];
  for (std::size_t i = (i1 + 1) % n;; i = (i + 1) % n) {
    s.segments.push_back(slicer::line_to(ring[i], slicer::Feature::Wall));
    if (i == i2) break;
  }
  s.width_mm = width;
  s.height_mm = height;
  return s;
}

double line_length(const PatternLine& l) {
  double len = 0.0;
  for (std::size_t i = 0; i + 1 < l.points.size(); ++i)
    len += (l.points[i + 1] - l.points[i]).norm();
  return len;
}

// A layer's pattern clipped to a fill boundary and joined, the innermost loops spliced in.
struct Joined {
  std::vector<slicer::Stroke> strands;  // with their loops, then the loops left over
  std::vector<FillPiece> pieces;
  int pattern_strands = 0;
  double pattern_length_mm = 0.0;
};

// `best` (the layer joined without seams, `over` the bound) again with sets of `seams`
// (patterns/lobe_seams.h: slits cut out of `fill`, or a narrow lobe's chords left out and its
// edge printed), `join(cut fill, slits, drops)` joining each try: first the spines (every cell
// off the way between two dead ends cut, so one strand runs from one to the other, there and
// back into each branch), then every dead end at once, then all but one or two (a strand may
// start or end in a lobe it need not leave; up to 12 and 6 dead ends, past which the choice is
// too wide to try), each with the first or second whole-cell slit or the drop where a cell has
// one, then one more cell at a time; a set is kept when it saves a strand and no slit has left
// its lobe without a half chord. Then each cut kept is dropped again where as many strands do
// without it (a body cut along with its legs), so the pattern changes no more than it must.
template <class Join, class Over>
Joined with_seams(const Region& fill, const LobeSeams& seams, const Over& over, Joined best,
                  const Join& join) {
  constexpr int kMaxTries = 64;  // joins per layer, bounding the work on a many-lobed part
  int tries = 0;
  using Cut = std::pair<std::size_t, std::size_t>;  // cell, variant
  std::vector<Cut> kept;
  bool fewer = false;  // an attempt with fewer seams than kept: as many strands will do
  const auto attempt = [&](const std::vector<Cut>& cuts) {
    ++tries;
    Region cut = fill, slits;
    std::vector<const Region*> drops;
    std::vector<Region> each;  // each slit, grown
    for (const auto& [c, v] : cuts) {
      const CellCut& x = seams.cells[c][v];
      if (x.drop) {
        drops.push_back(&x.region);
        continue;
      }
      cut = slicer::region_difference(cut, x.region);
      each.push_back(slicer::offset_region(x.region, 0.01));
      slits.insert(slits.end(), each.back().begin(), each.back().end());
    }
    Joined j = join(cut, slits, drops);
    // A slit no half chord ends on has left its lobe empty: no fewer strands are worth that.
    for (const Region& slit : each) {
      const bool used = std::any_of(j.pieces.begin(), j.pieces.end(), [&](const FillPiece& piece) {
        return slicer::contains(slit, piece.line.points.front()) ||
               slicer::contains(slit, piece.line.points.back());
      });
      if (!used) return false;
    }
    if (j.strands.size() > best.strands.size() ||
        (j.strands.size() == best.strands.size() && !fewer))
      return false;
    best = std::move(j);
    kept = cuts;
    return true;
  };
  const auto more = [&] { return over(best.strands) && tries < kMaxTries; };
  const std::size_t k = seams.dead_ends;
  // Each cell's cut in a mode: the first or the second whole-cell slit, or its chords left out
  // where the cell is narrow enough (else the first slit).
  const auto pick = [&](std::size_t c, std::size_t mode) -> std::size_t {
    const auto& cuts = seams.cells[c];
    if (mode < 2) return mode;
    return cuts.back().drop ? cuts.size() - 1 : 0;
  };
  // Spines first: every cell off the path between two dead ends cut, in each mode.
  for (const auto& off : seams.spines) {
    for (std::size_t mode = 0; mode < 3 && more(); ++mode) {
      if (mode == 2 &&
          std::none_of(off.begin(), off.end(), [&](std::size_t c) { return pick(c, 2) != 0; }))
        continue;
      std::vector<Cut> cuts;
      for (const std::size_t c : off) cuts.emplace_back(c, pick(c, mode));
      attempt(cuts);
    }
  }
  bool drops = false;  // mode 2 differs from mode 0
  for (std::size_t c = 0; c < k; ++c) drops = drops || pick(c, 2) != 0;
  for (std::size_t mode = 0; mode < (drops ? 3 : 2) && more(); ++mode) {
    const auto all_but = [&](std::size_t a, std::size_t b) {
      std::vector<Cut> cuts;
      for (std::size_t c = 0; c < k; ++c) {
        if (c != a && c != b) cuts.emplace_back(c, pick(c, mode));
      }
      return cuts;
    };
    if (k > 1) attempt(all_but(k, k));
    for (std::size_t a = 0; k > 2 && k <= 12 && a < k && more(); ++a) attempt(all_but(a, k));
    for (std::size_t a = 0; k > 3 && k <= 6 && a < k && more(); ++a) {
      for (std::size_t b = a + 1; b < k && more(); ++b) attempt(all_but(a, b));
    }
  }
  for (std::size_t c = 0; c < seams.cells.size() && more(); ++c) {
    if (std::any_of(kept.begin(), kept.end(), [&](const Cut& x) { return x.first == c; })) continue;
    for (std::size_t v = 0; v < seams.cells[c].size() && more(); ++v) {
      std::vector<Cut> cuts = kept;
      cuts.emplace_back(c, v);
      if (attempt(cuts)) break;
    }
  }
  fewer = true;
  for (std::size_t i = kept.size() > 1 ? kept.size() : 0; i-- > 0 && tries < kMaxTries + 12;) {
    std::vector<Cut> cuts = kept;
    cuts.erase(cuts.begin() + static_cast<std::ptrdiff_t>(i));
    attempt(cuts);
  }
  return best;
}

// A layer still over the bound: an open strand shorter than four nozzles (a stub left in a
// lobe too narrow to join it) is left out, shortest first, where its region has other
// strands over its bound, as a lattice's short pieces are: a start and a stop with hardly a
// bead between them. A stroke all wall (a thin feature's bead) is kept: it prints a feature.
// `out`'s pattern sums lose what is left out.
void drop_stubs(const Region& region, double nozzle_mm, std::vector<slicer::Stroke>& strands,
                LayerFill& out) {
  std::vector<int> parts;
  std::vector<int> over(region.size(), 0);
  for (std::size_t i = 0; i < region.size(); ++i)
    over[i] = -1 - static_cast<int>(region[i].holes.size());
  for (const auto& s : strands) {
    parts.push_back(part_holding(region, s));
    if (parts.back() >= 0) ++over[static_cast<std::size_t>(parts.back())];
  }
  for (;;) {
    std::size_t stub = strands.size();
    for (std::size_t i = 0; i < strands.size(); ++i) {
      const bool open = (strands[i].end_mm() - strands[i].start_mm).norm() > 1e-9;
      const bool bead =
          std::all_of(strands[i].segments.begin(), strands[i].segments.end(),
                      [](const auto& g) { return g.feature == slicer::Feature::Wall; });
      if (parts[i] < 0 || over[static_cast<std::size_t>(parts[i])] <= 0 || !open || bead) continue;
      const double len = slicer::stroke_length(strands[i]);
      if (len < 4.0 * nozzle_mm &&
          (stub == strands.size() || len < slicer::stroke_length(strands[stub])))
        stub = i;
    }
    if (stub == strands.size()) return;
    out.pattern_length_mm -= slicer::stroke_length(strands[stub]);
    --out.pattern_strands;
    --over[static_cast<std::size_t>(parts[stub])];
    strands.erase(strands.begin() + static_cast<std::ptrdiff_t>(stub));
    parts.erase(parts.begin() + static_cast<std::ptrdiff_t>(stub));
  }
}

}  // namespace

LayerFill fill_layer(const Region& region, const RegionPattern& p, int layer, int perimeters,
                     const Vec2& half, const std::vector<slicer::Stroke>& beads) {
  LayerFill out;
  out.regions = static_cast<int>(region.size());
  if (region.empty()) {
    out.strokes = beads;
    return out;
  }
  const double d = p.nozzle_mm, h = p.layer_height_mm;
  std::vector<slicer::Stroke> inner;  // the innermost perimeter level, spliced in below
  // Flat perimeter rings, as open lines: joined with the strands as pattern strands are.
  std::vector<slicer::Stroke> flats;
  for (int k = 0; k < perimeters; ++k) {
    for (const auto& ring : slicer::rings_of(slicer::offset_region(region, -(k + 0.5) * d))) {
      if (auto line = flat_ring(ring, d, h)) {
        flats.push_back(std::move(*line));
        continue;
      }
      (k + 1 == perimeters ? inner : out.strokes).push_back(ring_stroke(ring, d, h));
    }
  }
  // `slits`: seams cut out of `fill`, grown a little; half chords ending on one may be as
  // short as half a nozzle (a narrow lobe).
  const double min_half = 0.5 * d;
  const std::vector<PatternLine> lines = pattern_lines(p, layer, half);  // the same for every try
  // Only on a layer over the bound: ends linked across necks, thin beads joined in too (else
  // printed beside the strands, as they are).
  bool retry = false;
  // What links keep clear of, gathered once for every try: a splice the outer perimeters and
  // beads (its loops are its own), a neck link the loops too; on a retry the beads are strands.
  std::vector<slicer::Stroke> walls = out.strokes;
  walls.insert(walls.end(), beads.begin(), beads.end());
  std::vector<slicer::Stroke> loops_over = out.strokes;
  loops_over.insert(loops_over.end(), inner.begin(), inner.end());
  std::vector<slicer::Stroke> loops_within = loops_over;
  loops_within.insert(loops_within.end(), beads.begin(), beads.end());
  const auto join = [&](const Region& fill, const Region& slits,
                        const std::vector<const Region*>& drops) {
    Joined j;
    const RingSet rs = ring_set(slicer::rings_of(fill));
    std::vector<FillPiece> clipped = clip_to_rings(rs, lines);
    std::vector<char> keep(clipped.size(), 0);
    const auto in_slit = [&](const Vec2& q) {
      return !slits.empty() && slicer::contains(slits, q);
    };
    for (std::size_t i = 0; i < clipped.size(); ++i) {
      const PatternLine& l = clipped[i].line;
      const double len = line_length(l);
      // A corner or a node grazed: a strand of its own otherwise. A half chord ending on a
      // slit may be as short as min_half.
      keep[i] = len >= p.min_piece_mm ||
                (len >= min_half && (in_slit(l.points.front()) || in_slit(l.points.back())));
    }
    // The two halves of a chord a slit cuts are kept or left out together, so a lobe has as
    // many half chords on each side of its slit: its there-and-back needs that.
    for (std::size_t i = 0; i + 1 < clipped.size(); ++i) {
      const PatternLine &a = clipped[i].line, &b = clipped[i + 1].line;
      if (keep[i] != keep[i + 1] && a.order == b.order && in_slit(a.points.back()) &&
          in_slit(b.points.front()))
        keep[i] = keep[i + 1] = 0;
    }
    for (std::size_t i = 0; i < clipped.size(); ++i) {
      if (keep[i]) j.pieces.push_back(std::move(clipped[i]));
    }
    // A lobe whose chords are left out is printed round its edge instead.
    for (const Region* drop : drops) round_lobe(rs, *drop, j.pieces);
    for (const FillPiece& piece : j.pieces) j.pattern_length_mm += line_length(piece.line);
    std::vector<slicer::Stroke> strands = join_pieces(rs, j.pieces, {p.connector, d, h}, inner);
    j.pattern_strands = static_cast<int>(strands.size());
    // On a layer within the bound only a flat perimeter's line is linked (to anything).
    const std::size_t from = retry ? 0 : strands.size();
    strands.insert(strands.end(), flats.begin(), flats.end());
    if (retry) strands.insert(strands.end(), beads.begin(), beads.end());
    if (retry || !flats.empty()) {
      strands = link_across_necks(std::move(strands), retry ? loops_over : loops_within, region,
                                  {kNeckReach * d, 0.5 * d, 0.25 * d, from});
    }
    j.strands = splice_loops(inner, std::move(strands), d, retry ? out.strokes : walls);
    if (!retry) j.strands.insert(j.strands.end(), beads.begin(), beads.end());
    return j;
  };
  const Region fill = slicer::offset_region(region, -(perimeters + 0.5) * d);
  Joined best = join(fill, {}, {});
  // More strands than one per region and hole: a scaffold's dead-end lobes get seams.
  // Over the bound in some part (a region's count, as the slice summary takes it: the totals
  // would hide a part with a strand too many beside one with none).
  // The parts as a bead sees them, opened only when needed: a layer within the bound as
  // sliced, with no hole, is within it so too (opening only splits parts or drops slivers).
  const bool holes =
      std::any_of(region.begin(), region.end(), [](const auto& r) { return !r.holes.empty(); });
  std::optional<Region> parts;
  const auto over = [&](const std::vector<slicer::Stroke>& strands) {
    if (!parts && !holes && strands_over_bound(strands_per_region(region, strands)) == 0)
      return false;
    if (!parts) parts = bead_parts(region, d);
    return strands_over_bound(strands_per_region(*parts, strands)) > 0;
  };
  if (over(best.strands)) {
    retry = true;
    Joined linked = join(fill, {}, {});
    if (linked.strands.size() < best.strands.size()) best = std::move(linked);
  }
  if (over(best.strands) && p.lattice.empty()) {
    const LobeSeams seams = lobe_seams(fill, best.pieces, {d, p.pitch_mm, min_half});
    best = with_seams(fill, seams, over, std::move(best), join);
  }
  out.pattern_strands = best.pattern_strands;
  out.pattern_length_mm = best.pattern_length_mm;
  std::vector<slicer::Stroke>& strands = best.strands;
  if (over(strands)) drop_stubs(*parts, d, strands, out);
  out.strokes.insert(out.strokes.end(), strands.begin(), strands.end());
  return out;
}

namespace {

// Layer k filled when asked for, ordered from where layer k - 1 ended; the sums for the
// derived sizes accumulate as layers pass and complete the record with the last one.
class PartFillLayers final : public PartFillSource {
 public:
  PartFillLayers(PartFill part, RegionPattern p) : part_(std::move(part)), p_(std::move(p)) {
    record.generator = "slice";
    if (part_.layers.empty()) finish();
  }

  std::size_t layer_count() const override { return part_.layers.size(); }

  LayerFill fill(std::size_t k) const override {
    check_wall(part_.layers, k, p_.nozzle_mm, z_of(k));
    static const std::vector<slicer::Stroke> kNone;
    return fill_layer(part_.layers[k], p_, static_cast<int>(k), part_.perimeters,
                      part_.half_extent_mm,
                      k < part_.extra_strokes.size() ? part_.extra_strokes[k] : kNone);
  }

  const Region& region(std::size_t k) const override { return part_.layers.at(k); }

  slicer::Layer layer_from(std::size_t k, LayerFill f) override {
    slicer::Vec2 at = at_;
    slicer::Layer layer{z_of(k), p_.layer_height_mm,
                        slicer::nearest_first(std::move(f.strokes), at)};
    if (!layer.strokes.empty()) at_ = layer.strokes.back().end_mm();
    for (const auto& s : layer.strokes) deposited_ += slicer::stroke_length(s);
    pattern_length_ += f.pattern_length_mm;
    region_area_ += slicer::area_mm2(part_.layers[k]);
    regions_.push_back(f.regions);
    strands_.push_back(f.pattern_strands);
    slicer::progress_step(part_.progress, k + 1);
    if (k + 1 == part_.layers.size()) finish();
    return layer;
  }

 private:
  double z_of(std::size_t k) const { return (static_cast<double>(k) + 1.0) * p_.layer_height_mm; }

  void finish() {
    const double area = slicer::bead_area_mm2(p_.nozzle_mm, p_.layer_height_mm);
    const double sliced_volume = region_area_ * p_.layer_height_mm;
    const nlohmann::json derived = {
        {"pattern", p_.name},
        {"layers", part_.layers.size()},
        {"layer_height_mm", p_.layer_height_mm},
        {"regions_per_layer", regions_},
        {"pattern_strands_per_layer", strands_},
        {"part_volume_mm3", part_.volume_mm3},
        {"porosity", part_.volume_mm3 > 0 ? 1.0 - deposited_ * area / part_.volume_mm3 : 0.0},
        {"porosity_formula", "1 - (deposited length * bead area) / part volume"},
        {"pattern_porosity", p_.porosity},
        {"pattern_porosity_in_part",
         sliced_volume > 0 ? 1.0 - pattern_length_ * area / sliced_volume : 0.0},
        {"bead_area_mm2", area},
    };
    if (!record.derived.is_object()) record.derived = nlohmann::json::object();
    record.derived.update(derived);
    if (p_.pitch_mm > 0) record.derived["pitch_mm"] = p_.pitch_mm;
  }

  PartFill part_;
  RegionPattern p_;
  Vec2 at_ = Vec2::Zero();
  double deposited_ = 0.0, pattern_length_ = 0.0, region_area_ = 0.0;
  nlohmann::json regions_ = nlohmann::json::array(), strands_ = nlohmann::json::array();
};

}  // namespace

std::unique_ptr<PartFillSource> part_fill_layers(PartFill part, RegionPattern p) {
  return std::make_unique<PartFillLayers>(std::move(part), std::move(p));
}

slicer::Toolpath fill_part(const PartFill& part, const RegionPattern& p) {
  return slicer::collect(*part_fill_layers(part, p));
}

}  // namespace strand::patterns
