// The list of generators; add one line per design.
#include "patterns/registry.h"

#include "patterns/hexachiral.h"
#include "patterns/missing_rib.h"
#include "patterns/reentrant.h"
#include "patterns/scaffold.h"
#include "patterns/tetrachiral.h"

namespace strand::patterns {

const std::vector<GeneratorSpec>& generators() {
  static const std::vector<GeneratorSpec> kGenerators = {
      {"scaffold", "log-pile scaffold: one serpentine per layer, rotated by --angles",
       &scaffold_table, &scaffold_from_values},
      {"tetrachiral", "tetrachiral tensile specimen: one non-crossing strand per layer, grips at both ends",
       &tetrachiral_table, &tetrachiral_from_values},
      {"hexachiral", "hexachiral tensile specimen: one non-crossing strand per layer, grips at both ends",
       &hexachiral_table, &hexachiral_from_values},
      {"missing-rib", "missing-rib auxetic lattice: nodes rotated by +/- --angle, one closed strand per layer",
       &missing_rib_table, &missing_rib_from_values},
      {"reentrant", "re-entrant honeycomb: bands joined into one serpentine strand per layer",
       &reentrant_table, &reentrant_from_values},
  };
  return kGenerators;
}

const GeneratorSpec* find_generator(const std::string& name) {
  for (const auto& g : generators()) {
    if (g.name == name) return &g;
  }
  return nullptr;
}

}  // namespace strand::patterns
