// The layer stack every generator shares: --layer-height (a default ratio of the nozzle,
// allowed 0.5 to 1.0 x nozzle) and exactly one of --height or --layers.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "slicer/params.h"

namespace strand::patterns {

struct LayerStack {
  double layer_height_mm = 0.0;
  int layers = 1;  // from --layers, or --height rounded to the nearest whole layer (>= 1)
};

// Appends the rows every generator shares: height, layers, layer-height (its default shown
// as `ratio_text`, e.g. "0.8 * nozzle") and speed.
slicer::ParamTable with_layer_rows(slicer::ParamTable table, const std::string& ratio_text);

// Adds "give exactly one of --a or --b" (or "missing") to `problems` unless exactly one is set.
void require_one_of(const std::string& table, const nlohmann::json& values, const char* a,
                    const char* b, std::vector<std::string>& problems);

// Reads the layer stack from checked values; a layer height outside 0.5-1.0 x nozzle is
// added to `problems`. Precondition: exactly one of "height" and "layers" is present.
LayerStack layer_stack_from(const std::string& table, const nlohmann::json& values,
                            double nozzle_mm, double default_ratio,
                            std::vector<std::string>& problems);

}  // namespace strand::patterns
