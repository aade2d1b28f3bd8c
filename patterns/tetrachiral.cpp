// Tetrachiral specimen: the shared chiral generator on a square lattice, plus the
// thesis' porosity formula reported beside the measured one.
#include "patterns/tetrachiral.h"

#include <cmath>

#include "slicer/units.h"

namespace strand::patterns {

double tetrachiral_thesis_porosity(const ChiralParams& p, double r) {
  const double l = p.cell_mm, d = p.nozzle_mm, h = p.layer_height_mm;
  const double alfa = std::atan(2 * r / l);
  return 1.0 - (2 * l * d / std::cos(alfa) + slicer::kPi * r * (3 * h + 2 * d)) / (l * l);
}

namespace {

void add_thesis_porosity(nlohmann::json& derived, ChiralParams p) {
  p.cell_mm = derived.value("cell_mm", p.cell_mm);
  derived["porosity_thesis"] = tetrachiral_thesis_porosity(p, derived.at("node_radius_mm").get<double>());
  derived["porosity_thesis_formula"] = "1 - (2 l d / cos(atan(2r/l)) + pi r (3h + 2d)) / l^2";
}

slicer::Toolpath with_thesis_porosity(slicer::Toolpath t, const ChiralParams& p) {
  add_thesis_porosity(t.derived, p);
  return t;
}

}  // namespace

std::unique_ptr<slicer::LayerSource> tetrachiral_layers(const ChiralParams& p) {
  auto t = chiral_layers(ChiralKind::Tetra, p);
  add_thesis_porosity(t->record.derived, p);
  return t;
}

slicer::Toolpath generate_tetrachiral(const ChiralParams& p) { return slicer::collect(*tetrachiral_layers(p)); }

slicer::Toolpath generate_tetrachiral_wrapped(const ChiralParams& p, double period_mm) {
  const WrapFit fit = fit_around("tetrachiral", period_mm, p.cell_mm,
                                 chiral_wrap_rule(ChiralKind::Tetra, p));
  return with_thesis_porosity(generate_chiral_ring(ChiralKind::Tetra, p, fit), p);
}

}  // namespace strand::patterns
