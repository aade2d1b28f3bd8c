// Re-entrant honeycomb geometry as a serpentine of wavy bands. Band k lies between rib
// lines k and k+1; going up it crosses every row boundary Z_r (r = -1 .. rows-1) on one
// inclined rib and climbs each row on the vertical rib of whichever of its two lines has one.
// Where a line carries a vertical rib on both sides (interior lines), each band uses its own
// copy, half a nozzle off the line, and its inclined ribs are clipped there so they keep
// the exact angle.
#include "patterns/reentrant.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "patterns/wrap_fit.h"
#include "slicer/units.h"

namespace strand::patterns {

using slicer::Feature;
using slicer::Vec2;

namespace {

class BandBuilder {
 public:
  // `ring`: the lattice wrapped round a cylinder, where line 2 cols is line 0 again, so
  // every line is interior.
  BandBuilder(const ReentrantParams& p, const ReentrantGeometry& g, bool ring)
      : p_(p), g_(g), ring_(ring) {}

  // Points of band k from the bottom row boundary to the top one.
  std::vector<Vec2> band(int k) const {
    std::vector<Vec2> pts;
    for (int r = -1; r < p_.rows; ++r) {
      const int entry = (k + r) % 2 != 0 ? k : k + 1;  // has row r's vertical rib below
      const int exit = entry == k ? k + 1 : k;         // has row r+1's vertical rib above
      const Vec2 a(line_x(entry), boundary_y(r, entry));
      const Vec2 b(line_x(exit), boundary_y(r, exit));
      pts.push_back(clipped(a, b, r >= 0 ? copy_offset(k, entry) : 0.0));
      pts.push_back(clipped(a, b, r + 1 < p_.rows ? copy_offset(k, exit) : 0.0, true));
    }
    return pts;
  }

 private:
  double line_x(int j) const { return (j - p_.cols) * p_.cell_width_mm / 2; }
  // Row centres, shifted so the deposited centre lines are centred on y = 0.
  double row_y(int r) const { return (r - (p_.rows - 1) / 2.0) * g_.row_pitch_mm - g_.bottom_lift_mm / 2; }
  // Nominal point of row boundary Z_r (top of row r) on line j: the top of row r's vertical
  // rib if the line has one there (j + r odd), else the re-entrant tip, delta lower.
  double boundary_y(int r, int j) const {
    const double top = row_y(r) + p_.cell_height_mm / 2;
    return (j + r) % 2 != 0 ? top : top - g_.tip_depth_mm;
  }
  // Where band k's copy of the vertical rib on line j sits, relative to the line: half a
  // nozzle towards the band on interior lines, on the line itself at the two outer lines.
  double copy_offset(int k, int j) const {
    if (!ring_ && (j == 0 || j == g_.bands)) return 0.0;
    return j == k ? p_.nozzle_mm / 2 : -p_.nozzle_mm / 2;
  }
  // The point of rib a-b that lies `offset` (signed, along x) from a (or from b).
  static Vec2 clipped(const Vec2& a, const Vec2& b, double offset, bool from_b = false) {
    const Vec2& base = from_b ? b : a;
    const Vec2& other = from_b ? a : b;
    const double t = offset / (other.x() - base.x());
    return base + t * (other - base);
  }

  const ReentrantParams& p_;
  const ReentrantGeometry& g_;
  bool ring_ = false;
};

// The serpentine: even bands up, odd bands down; neighbours share their joining tip. On a
// ring the last band comes down to the first band's start one period on: a closed strand.
slicer::Stroke serpentine(const ReentrantParams& p, const ReentrantGeometry& g, bool ring = false) {
  const BandBuilder builder(p, g, ring);
  slicer::Stroke s;
  bool first = true;
  for (int k = 0; k < g.bands; ++k) {
    std::vector<Vec2> pts = builder.band(k);
    if (k % 2 != 0) std::reverse(pts.begin(), pts.end());
    for (const Vec2& q : pts) {
      if (first) {
        s.start_mm = q;
        first = false;
      } else if ((q - s.end_mm()).norm() > 1e-9) {
        s.segments.push_back(slicer::line_to(q, Feature::Ligament));
      }
    }
  }
  s.width_mm = p.nozzle_mm;
  s.height_mm = p.layer_height_mm;
  return s;
}

}  // namespace

ReentrantGeometry reentrant_geometry(const ReentrantParams& p) {
  ReentrantGeometry g;
  const double theta = slicer::deg_to_rad(p.angle_deg);
  const double half_w = p.cell_width_mm / 2;
  g.tip_depth_mm = half_w * std::tan(theta);
  g.row_pitch_mm = p.cell_height_mm - g.tip_depth_mm;
  g.bands = 2 * p.cols;
  g.width_mm = p.cols * p.cell_width_mm + p.nozzle_mm;
  g.bottom_lift_mm = p.nozzle_mm / 2 * std::tan(theta);
  g.depth_mm = (p.rows - 1) * g.row_pitch_mm + p.cell_height_mm - g.bottom_lift_mm + p.nozzle_mm;
  g.height_mm = p.layers * p.layer_height_mm;
  g.inclined_rib_mm = half_w / std::cos(theta);
  g.tip_gap_mm = p.cell_height_mm - 2 * g.tip_depth_mm;
  g.band_gap_mm = g.bands >= 3 ? half_w - p.nozzle_mm : half_w - p.nozzle_mm / 2;
  return g;
}

namespace {

// Header and report figures, from the strand actually laid down.
nlohmann::json reentrant_report(const ReentrantParams& p, const ReentrantGeometry& g, const slicer::Stroke& layer) {
  const double per_layer = slicer::stroke_length(layer);
  const double area = slicer::bead_area_mm2(p.nozzle_mm, p.layer_height_mm);
  const double density = per_layer * p.layers * area / (g.width_mm * g.depth_mm * g.height_mm);
  const double theta = slicer::deg_to_rad(p.angle_deg);
  return {
      {"footprint_mm", {g.width_mm, g.depth_mm}},
      {"height_mm", g.height_mm},
      {"layers", p.layers},
      {"layer_height_mm", p.layer_height_mm},
      {"cell_width_mm", p.cell_width_mm},
      {"cell_height_mm", p.cell_height_mm},
      {"angle_deg", p.angle_deg},
      {"tip_depth_mm", g.tip_depth_mm},
      {"row_pitch_mm", g.row_pitch_mm},
      {"inclined_rib_mm", g.inclined_rib_mm},
      {"inclined_rib_printed_mm", (p.cell_width_mm / 2 - p.nozzle_mm) / std::cos(theta)},
      {"vertical_rib_passes", 2},
      {"tip_gap_mm", g.tip_gap_mm},
      {"band_gap_mm", g.band_gap_mm},
      {"bands", g.bands},
      {"filament_length_per_layer_mm", per_layer},
      {"filament_length_mm", per_layer * p.layers},
      {"bead_area_mm2", area},
      {"relative_density", density},
      {"porosity", 1.0 - density},
      {"porosity_formula", "1 - (filament length * bead area) / (width * depth * height)"},
      {"strands_per_layer", 1},
      {"strands_why",
       "bands between neighbouring rib lines join at the free tips of the top and bottom rows "
       "(rows even), interior vertical ribs get one pass per band side by side: one open strand"},
  };
}

// Layers alternate direction, so each starts where the previous one ended.
std::unique_ptr<slicer::LayerSource> stacked(const ReentrantParams& p, const slicer::Stroke& forward) {
  std::vector<std::vector<slicer::Stroke>> designs = {{forward}, {slicer::reversed(forward)}};
  auto t = std::make_unique<slicer::RepeatedLayers>(std::move(designs), static_cast<std::size_t>(std::max(p.layers, 0)),
                                                    p.layer_height_mm);
  t->record.generator = "reentrant";
  return t;
}

// Moves a stroke along y so its points' extent is centred on y = 0; returns that extent.
double centre_in_y(slicer::Stroke& s) {
  double lo = s.start_mm.y(), hi = lo;
  for (const auto& seg : s.segments) lo = std::min(lo, seg.end_mm.y()), hi = std::max(hi, seg.end_mm.y());
  const Vec2 shift(0.0, -(lo + hi) / 2);
  s.start_mm += shift;
  for (auto& seg : s.segments) seg.end_mm += shift;
  return hi - lo;
}

}  // namespace

std::unique_ptr<slicer::LayerSource> reentrant_layers(const ReentrantParams& p) {
  const ReentrantGeometry g = reentrant_geometry(p);
  const slicer::Stroke forward = serpentine(p, g);
  auto t = stacked(p, forward);
  t->record.derived = reentrant_report(p, g, forward);
  return t;
}

slicer::Toolpath generate_reentrant(const ReentrantParams& p) { return slicer::collect(*reentrant_layers(p)); }

slicer::Toolpath generate_reentrant_wrapped(const ReentrantParams& given, double period_mm) {
  ReentrantParams p = given;
  const double d = p.nozzle_mm;
  WrapRule rule{2, 1, 500, 4 * d, "2 columns of bands each, so bands have distinct neighbours"};
  rule.max_cell_mm = (p.cell_height_mm - d) / std::tan(slicer::deg_to_rad(p.angle_deg));
  const WrapFit fit = fit_around("reentrant", period_mm, p.cell_width_mm, rule);
  p.cell_width_mm = fit.cell_mm;
  p.cols = fit.cells;
  ReentrantGeometry g = reentrant_geometry(p);
  slicer::Stroke forward = serpentine(p, g, true);
  g.width_mm = period_mm;
  g.depth_mm = centre_in_y(forward) + d;  // every line interior: both end rows are clipped
  g.band_gap_mm = p.cell_width_mm / 2 - d;  // no outer lines: every band's ribs are copies
  slicer::Toolpath t = slicer::collect(*stacked(p, forward));
  t.derived = reentrant_report(p, g, forward);
  t.derived["strands_why"] =
      "bands between neighbouring rib lines join at the free tips of the end rows, the last "
      "band back to the first across the seam; every vertical rib gets one pass per band side "
      "by side: one closed strand";
  add_wrap_report(t.derived, fit, "cell width (cell height and angle kept)");
  return t;
}

}  // namespace strand::patterns
