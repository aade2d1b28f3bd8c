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

slicer::Toolpath generate_tetrachiral(const ChiralParams& p) {
  slicer::Toolpath t = generate_chiral(ChiralKind::Tetra, p);
  t.derived["porosity_thesis"] =
      tetrachiral_thesis_porosity(p, t.derived.at("node_radius_mm").get<double>());
  t.derived["porosity_thesis_formula"] = "1 - (2 l d / cos(atan(2r/l)) + pi r (3h + 2d)) / l^2";
  return t;
}

}  // namespace strand::patterns
