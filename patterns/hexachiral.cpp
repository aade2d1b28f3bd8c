// Hexachiral specimen: the shared chiral generator on a triangular lattice.
#include "patterns/hexachiral.h"

namespace strand::patterns {

std::unique_ptr<slicer::LayerSource> hexachiral_layers(const ChiralParams& p) {
  return chiral_layers(ChiralKind::Hexa, p);
}

slicer::Toolpath generate_hexachiral(const ChiralParams& p) { return generate_chiral(ChiralKind::Hexa, p); }

slicer::Toolpath generate_hexachiral_wrapped(const ChiralParams& p, double period_mm) {
  const WrapFit fit = fit_around("hexachiral", period_mm, p.cell_mm,
                                 chiral_wrap_rule(ChiralKind::Hexa, p));
  return generate_chiral_ring(ChiralKind::Hexa, p, fit);
}

}  // namespace strand::patterns
