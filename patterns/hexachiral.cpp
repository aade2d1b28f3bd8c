// Hexachiral specimen: the shared chiral generator on a triangular lattice.
#include "patterns/hexachiral.h"

namespace strand::patterns {

slicer::Toolpath generate_hexachiral(const ChiralParams& p) {
  return generate_chiral(ChiralKind::Hexa, p);
}

}  // namespace strand::patterns
