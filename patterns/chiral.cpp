// Chiral specimen generator shared by both lattices: lattice, rings, one strand per layer
// (identical layers stacked), and the geometry report measured on the deposited strand.
#include "patterns/chiral.h"

#include <algorithm>
#include <map>

#include "patterns/chiral_lattice.h"
#include "patterns/chiral_strand.h"
#include "slicer/units.h"

namespace strand::patterns {

namespace {

ChiralLattice (*lattice_maker(ChiralKind kind))(int, int, double) {
  return kind == ChiralKind::Tetra ? &tetrachiral_lattice : &hexachiral_lattice;
}

NodeRings rings_of(const ChiralParams& p) {
  return node_rings(p.core_mm, p.nozzle_mm, p.layer_height_mm, p.passes);
}

// Bounds of the strand's segment ends (lines only reach the frame and grips, which
// enclose every arc), with the bead width added on every side.
std::pair<slicer::Vec2, slicer::Vec2> bead_bounds(const std::vector<slicer::Stroke>& strokes,
                                                  double nozzle_mm, bool with_grips) {
  slicer::Vec2 lo = slicer::Vec2::Constant(1e300), hi = -lo;
  for (const auto& s : strokes) {
    slicer::Vec2 at = s.start_mm;
    for (const auto& seg : s.segments) {
      if (with_grips || (seg.feature != slicer::Feature::Grip)) {
        lo = lo.cwiseMin(at).cwiseMin(seg.end_mm), hi = hi.cwiseMax(at).cwiseMax(seg.end_mm);
      }
      at = seg.end_mm;
    }
  }
  const slicer::Vec2 half = slicer::Vec2::Constant(nozzle_mm / 2);
  return {lo - half, hi + half};
}

// `period_mm` > 0: a ring lattice, whose width is the period (its strand runs past the seam).
nlohmann::json derived(ChiralKind kind, const ChiralParams& p, const NodeRings& r,
                       const std::vector<slicer::Stroke>& strokes, double period_mm = 0.0) {
  std::map<std::string, double> by_feature;
  double lattice_len = 0, total = 0;
  for (const auto& s : strokes) {
    slicer::Vec2 at = s.start_mm;
    for (const auto& seg : s.segments) {
      const double len = slicer::segment_length(at, seg);
      by_feature[slicer::to_string(seg.feature)] += len;
      total += len;
      if (seg.feature != slicer::Feature::Grip) lattice_len += len;
      at = seg.end_mm;
    }
  }
  auto [lo, hi] = bead_bounds(strokes, p.nozzle_mm, true);
  auto [llo, lhi] = bead_bounds(strokes, p.nozzle_mm, false);
  if (period_mm > 0) lo.x() = llo.x() = -period_mm / 2, hi.x() = lhi.x() = period_mm / 2;
  const double height = p.layers * p.layer_height_mm;
  const double area = slicer::bead_area_mm2(p.nozzle_mm, p.layer_height_mm);
  const double density = lattice_len * area / ((lhi - llo).prod() * p.layer_height_mm);
  nlohmann::json lengths = nlohmann::json::object();
  for (const auto& [k, v] : by_feature) lengths[k] = v;
  return {
      {"size_mm", {hi.x() - lo.x(), hi.y() - lo.y(), height}},
      {"lattice_size_mm", {lhi.x() - llo.x(), lhi.y() - llo.y()}},
      {"cells", {p.cols, p.rows}},
      {"layers", p.layers},
      {"layer_height_mm", p.layer_height_mm},
      {"node_radius_mm", r.middle_mm},
      {"node_pass_radii_mm", r.pass_mm},
      {"ligament_attach_radius_mm", r.attach_mm},
      {"node_ring_thickness_mm", r.ring_width_mm},
      {"ligament_thickness_mm", p.nozzle_mm},
      {"node_to_ligament_thickness", r.ring_width_mm / p.nozzle_mm},
      {"ligament_angle_deg", slicer::rad_to_deg(ligament_angle_rad(p.cell_mm, r.attach_mm))},
      {"min_cell_mm", chiral_min_cell_mm(kind, p)},
      {"strands_per_layer", strokes.size()},
      {"filament_length_per_layer_mm", total},
      {"filament_length_by_feature_mm", lengths},
      {"filament_length_mm", total * p.layers},
      {"bead_area_mm2", area},
      {"relative_density", density},
      {"porosity", 1.0 - density},
      {"porosity_formula",
       "1 - (filament length without grips * bead area) / (lattice width * length * layer height)"},
  };
}

}  // namespace

double chiral_min_cell_mm(ChiralKind kind, const ChiralParams& p) {
  return min_cell_mm(lattice_maker(kind), rings_of(p), p.nozzle_mm);
}

namespace {

std::unique_ptr<slicer::LayerSource> stacked(ChiralKind kind, const ChiralParams& p,
                                             const std::vector<slicer::Stroke>& strokes) {
  auto t = std::make_unique<slicer::RepeatedLayers>(std::vector<std::vector<slicer::Stroke>>{strokes},
                                                    static_cast<std::size_t>(std::max(p.layers, 0)),
                                                    p.layer_height_mm);
  t->record.generator = kind == ChiralKind::Tetra ? "tetrachiral" : "hexachiral";
  return t;
}

}  // namespace

std::unique_ptr<slicer::LayerSource> chiral_layers(ChiralKind kind, const ChiralParams& p) {
  const NodeRings rings = rings_of(p);
  const ChiralLattice lattice = lattice_maker(kind)(p.cols, p.rows, p.cell_mm);
  const std::vector<slicer::Stroke> strokes =
      chiral_layer(lattice, rings, {p.nozzle_mm, p.layer_height_mm, p.grip_mm});
  auto t = stacked(kind, p, strokes);
  t->record.derived = derived(kind, p, rings, strokes);
  return t;
}

slicer::Toolpath generate_chiral(ChiralKind kind, const ChiralParams& p) {
  return slicer::collect(*chiral_layers(kind, p));
}

WrapRule chiral_wrap_rule(ChiralKind kind, const ChiralParams& p) {
  WrapRule rule;
  rule.min_cell_mm = chiral_min_cell_mm(kind, p);
  if (kind == ChiralKind::Tetra) {
    rule.min_cells = 4;
    rule.step = 2;
    rule.count_why =
        "an even number: the frame at each end pairs the end nodes, which have 3 ligaments";
  } else {
    rule.count_why = "so neighbours round the cylinder are distinct nodes";
  }
  return rule;
}

slicer::Toolpath generate_chiral_ring(ChiralKind kind, ChiralParams p, const WrapFit& fit) {
  p.cell_mm = fit.cell_mm;
  p.cols = fit.cells;
  const NodeRings rings = rings_of(p);
  const auto ring = kind == ChiralKind::Tetra ? &tetrachiral_ring : &hexachiral_ring;
  const ChiralLattice lattice = ring(fit.cells, p.rows, p.cell_mm);
  const std::vector<slicer::Stroke> strokes =
      chiral_layer(lattice, rings, {p.nozzle_mm, p.layer_height_mm, p.grip_mm});
  slicer::Toolpath t = slicer::collect(*stacked(kind, p, strokes));
  t.derived = derived(kind, p, rings, strokes, fit.period_mm);
  t.derived["cell_mm"] = p.cell_mm;
  add_wrap_report(t.derived, fit, "node spacing (cell, both directions, cols ignored)");
  return t;
}

}  // namespace strand::patterns
