// The list of generators; add one line per design.
#include "patterns/registry.h"

#include "patterns/hexachiral.h"
#include "patterns/missing_rib.h"
#include "patterns/reentrant.h"
#include "patterns/scaffold.h"
#include "patterns/tetrachiral.h"

namespace strand::patterns {

namespace {

// The one generate-and-record step: parameters from checked values, the design's pure
// generator, and the values recorded in the toolpath for headers and reports.
template <auto ParamsFrom, auto Generate>
slicer::Toolpath generate_recorded(const nlohmann::json& values) {
  slicer::Toolpath t = Generate(ParamsFrom(values));
  t.parameters = values;
  return t;
}

}  // namespace

const std::vector<GeneratorSpec>& generators() {
  static const std::vector<GeneratorSpec> kGenerators = {
      {"scaffold", "log-pile scaffold: one serpentine per layer, rotated by --angles",
       &scaffold_table, &generate_recorded<&scaffold_params_from, &generate_scaffold>},
      {"tetrachiral", "tetrachiral tensile specimen: one non-crossing strand per layer, grips at both ends",
       &tetrachiral_table, &generate_recorded<&tetrachiral_params_from, &generate_tetrachiral>},
      {"hexachiral", "hexachiral tensile specimen: one non-crossing strand per layer, grips at both ends",
       &hexachiral_table, &generate_recorded<&hexachiral_params_from, &generate_hexachiral>},
      {"missing-rib", "missing-rib auxetic lattice: nodes rotated by +/- --angle, one closed strand per layer",
       &missing_rib_table, &generate_recorded<&missing_rib_params_from, &generate_missing_rib>},
      {"reentrant", "re-entrant honeycomb: bands joined into one serpentine strand per layer",
       &reentrant_table, &generate_recorded<&reentrant_params_from, &generate_reentrant>},
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
