// Hexachiral tensile specimen: circular nodes on a triangular lattice (rows l sin 60
// apart, odd rows shifted by l / 2), six tangent ligaments per node, one continuous
// non-crossing strand per layer with grip tabs at both ends.
#pragma once

#include <nlohmann/json.hpp>

#include "patterns/chiral.h"

namespace strand::patterns {

std::unique_ptr<slicer::LayerSource> hexachiral_layers(const ChiralParams& p);
slicer::Toolpath generate_hexachiral(const ChiralParams& p);
// `--wrap full`: a sleeve periodic in x with period `period_mm`, at least 3 cells round it
// (cell adjusted to fit). Its end rows have even degree, so no frame; a grip band hangs on
// a loop at one end node.
slicer::Toolpath generate_hexachiral_wrapped(const ChiralParams& p, double period_mm);

const slicer::ParamTable& hexachiral_table();
ChiralParams hexachiral_params_from(const nlohmann::json& values);

}  // namespace strand::patterns
