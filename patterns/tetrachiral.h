// Tetrachiral tensile specimen: circular nodes on a square grid, four tangent ligaments
// per node, one continuous non-crossing strand per layer with grip tabs at both ends.
#pragma once

#include <nlohmann/json.hpp>

#include "patterns/chiral.h"

namespace strand::patterns {

std::unique_ptr<slicer::LayerSource> tetrachiral_layers(const ChiralParams& p);
slicer::Toolpath generate_tetrachiral(const ChiralParams& p);
// `--wrap full`: a sleeve periodic in x with period `period_mm`, an even number of cells
// round it (cell adjusted to fit), frame and grip bands only at the two ends.
slicer::Toolpath generate_tetrachiral_wrapped(const ChiralParams& p, double period_mm);
// The thesis' porosity estimate P = 1 - (2 l d / cos a + pi r (3h + 2d)) / l^2, a = atan(2r/l).
double tetrachiral_thesis_porosity(const ChiralParams& p, double node_radius_mm);

const slicer::ParamTable& tetrachiral_table();
ChiralParams tetrachiral_params_from(const nlohmann::json& values);

}  // namespace strand::patterns
