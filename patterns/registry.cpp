// The list of generators; add one line per design.
#include "patterns/registry.h"

#include "patterns/hexachiral.h"
#include "patterns/missing_rib.h"
#include "patterns/reentrant.h"
#include "patterns/scaffold.h"
#include "patterns/tetrachiral.h"
#include "slicer/input_error.h"

namespace strand::patterns {

namespace {

std::size_t segment_count(const slicer::Toolpath& t) {
  std::size_t n = 0;
  for (const auto& l : t.layers) {
    for (const auto& s : l.strokes) n += s.segments.size() + 1;
  }
  return n;
}

void refuse_oversized(const std::string& name, int layers, std::size_t segments) {
  throw InputError(name + ".layers = " + std::to_string(layers) + ": the specimen would have about " +
                   std::to_string(segments) + " moves, more than the limit of " +
                   std::to_string(kMaxToolpathSegments) + "; use fewer layers or a smaller part");
}

// The one generate-and-record step: parameters from checked values, the design's pure
// generator, and the values recorded in the toolpath for headers and reports. Work is
// bounded first: two layers cost little and every further layer repeats them, so a stack
// that would exceed kMaxToolpathSegments is refused before it is built.
template <auto ParamsFrom, auto Generate>
slicer::Toolpath generate_recorded(const nlohmann::json& values) {
  auto params = ParamsFrom(values);
  if (params.layers > 2) {
    auto trial = params;
    trial.layers = 2;
    const std::size_t per_layer = segment_count(Generate(trial)) / 2 + 1;
    const std::size_t total = per_layer * static_cast<std::size_t>(params.layers);
    if (total > kMaxToolpathSegments) refuse_oversized(Generate(trial).generator, params.layers, total);
  }
  slicer::Toolpath t = Generate(params);
  if (segment_count(t) > kMaxToolpathSegments) {
    refuse_oversized(t.generator, params.layers, segment_count(t));
  }
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
