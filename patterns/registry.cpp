// The list of generators; add one line per design.
#include "patterns/registry.h"

#include "patterns/collapse_test.h"
#include "patterns/fusion_test.h"
#include "patterns/hexachiral.h"
#include "patterns/line_matrix.h"
#include "patterns/missing_rib.h"
#include "patterns/pore_test.h"
#include "patterns/reentrant.h"
#include "patterns/scaffold.h"
#include "patterns/tetrachiral.h"
#include "slicer/input_error.h"

namespace strand::patterns {

namespace {

std::size_t segment_count(const slicer::Layer& l) {
  std::size_t n = 0;
  for (const auto& s : l.strokes) n += s.segments.size() + 1;
  return n;
}

std::size_t segment_count(const slicer::Toolpath& t) {
  std::size_t n = 0;
  for (const auto& l : t.layers) n += segment_count(l);
  return n;
}

[[noreturn]] void refuse_oversized(const std::string& name, int layers, std::size_t segments) {
  throw InputError(name + ".layers = " + std::to_string(layers) + ": the specimen would have about " +
                   std::to_string(segments) + " moves, more than the limit of " +
                   std::to_string(kMaxToolpathSegments) + "; use fewer layers or a smaller part");
}

// Work is bounded before a stack is made: two layers cost little and every further layer
// repeats them, so a stack that would exceed kMaxToolpathSegments is refused first. The
// layers are counted as they pass too; the last one throws if the stack came out larger.
class BoundedLayers final : public slicer::LayerSource {
 public:
  BoundedLayers(std::unique_ptr<slicer::LayerSource> inner, int layers)
      : inner_(std::move(inner)), layers_(layers) {
    record = std::move(inner_->record);
  }
  std::size_t layer_count() const override { return inner_->layer_count(); }
  slicer::Layer layer(std::size_t index) override {
    slicer::Layer l = inner_->layer(index);
    segments_ += segment_count(l);
    if (index + 1 == layer_count() && segments_ > kMaxToolpathSegments) {
      refuse_oversized(record.generator, layers_, segments_);
    }
    return l;
  }

 private:
  std::unique_ptr<slicer::LayerSource> inner_;
  int layers_;
  std::size_t segments_ = 0;
};

template <class Params, class Make>
std::unique_ptr<slicer::LayerSource> layers_bounded(const Params& params, const Make& make) {
  if (params.layers > 2) {
    auto trial = params;
    trial.layers = 2;
    const slicer::Toolpath two = slicer::collect(*make(trial));
    const std::size_t per_layer = segment_count(two) / 2 + 1;
    const std::size_t total = per_layer * static_cast<std::size_t>(params.layers);
    if (total > kMaxToolpathSegments) refuse_oversized(two.generator, params.layers, total);
  }
  return std::make_unique<BoundedLayers>(make(params), params.layers);
}

// The one generate-and-record step: parameters from checked values, the design's layer
// source (bounded), and the values recorded for headers and reports.
template <auto ParamsFrom, auto Layers>
std::unique_ptr<slicer::LayerSource> layers_recorded(const nlohmann::json& values) {
  auto t = layers_bounded(ParamsFrom(values), [](const auto& p) { return Layers(p); });
  t->record.parameters = values;
  return t;
}

template <auto ParamsFrom, auto Layers>
slicer::Toolpath generate_recorded(const nlohmann::json& values) {
  return slicer::collect(*layers_recorded<ParamsFrom, Layers>(values));
}

// The same for a design's periodic variant (`--wrap full`), made whole.
template <auto ParamsFrom, auto GenerateWrapped>
slicer::Toolpath generate_wrapped_recorded(const nlohmann::json& values, double period_mm) {
  const auto params = ParamsFrom(values);
  auto make = [&](const auto& p) {
    return std::make_unique<slicer::ToolpathLayers>(GenerateWrapped(p, period_mm));
  };
  auto source = layers_bounded(params, make);
  slicer::Toolpath t = slicer::collect(*source);
  t.parameters = values;
  return t;
}

}  // namespace

const std::vector<GeneratorSpec>& generators() {
  static const std::vector<GeneratorSpec> kGenerators = {
      {"scaffold", "log-pile scaffold: one serpentine per layer, rotated by --angles",
       &scaffold_table, &generate_recorded<&scaffold_params_from, &scaffold_layers>,
       &generate_wrapped_recorded<&scaffold_params_from, &generate_scaffold_wrapped>,
       &layers_recorded<&scaffold_params_from, &scaffold_layers>},
      {"tetrachiral", "tetrachiral tensile specimen: one non-crossing strand per layer, grips at both ends",
       &tetrachiral_table, &generate_recorded<&tetrachiral_params_from, &tetrachiral_layers>,
       &generate_wrapped_recorded<&tetrachiral_params_from, &generate_tetrachiral_wrapped>,
       &layers_recorded<&tetrachiral_params_from, &tetrachiral_layers>},
      {"hexachiral", "hexachiral tensile specimen: one non-crossing strand per layer, grips at both ends",
       &hexachiral_table, &generate_recorded<&hexachiral_params_from, &hexachiral_layers>,
       &generate_wrapped_recorded<&hexachiral_params_from, &generate_hexachiral_wrapped>,
       &layers_recorded<&hexachiral_params_from, &hexachiral_layers>},
      {"missing-rib", "missing-rib auxetic lattice: nodes rotated by +/- --angle, one closed strand per layer",
       &missing_rib_table, &generate_recorded<&missing_rib_params_from, &missing_rib_layers>,
       &generate_wrapped_recorded<&missing_rib_params_from, &generate_missing_rib_wrapped>,
       &layers_recorded<&missing_rib_params_from, &missing_rib_layers>},
      {"reentrant", "re-entrant honeycomb: bands joined into one serpentine strand per layer",
       &reentrant_table, &generate_recorded<&reentrant_params_from, &reentrant_layers>,
       &generate_wrapped_recorded<&reentrant_params_from, &generate_reentrant_wrapped>,
       &layers_recorded<&reentrant_params_from, &reentrant_layers>},
      {"line-matrix", "ink test: lines in a grid of --speeds x --flows with fiducial marks, to measure from a photo",
       &line_matrix_table, &generate_recorded<&line_matrix_params_from, &line_matrix_layers>, nullptr,
       &layers_recorded<&line_matrix_params_from, &line_matrix_layers>},
      {"pore-test", "ink test: an N x N grid of square pores (0/90 log-pile) with fiducial marks, to measure Pr from a photo",
       &pore_test_table, &generate_recorded<&pore_test_params_from, &pore_test_layers>, nullptr,
       &layers_recorded<&pore_test_params_from, &pore_test_layers>},
      {"fusion-test", "ink test: one meander whose filament spacing shrinks, with fiducial marks, to see where filaments fuse",
       &fusion_test_table, &generate_recorded<&fusion_test_params_from, &fusion_test_layers>, nullptr,
       &layers_recorded<&fusion_test_params_from, &fusion_test_layers>},
      {"collapse-test", "ink test: pillars with growing gaps and one filament across their tops, with fiducial marks",
       &collapse_test_table, &generate_recorded<&collapse_test_params_from, &collapse_test_layers>, nullptr,
       &layers_recorded<&collapse_test_params_from, &collapse_test_layers>},
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
