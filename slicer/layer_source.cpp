// Collecting a layer source, and the two sources every design shares.
#include "slicer/layer_source.h"

namespace strand::slicer {

Toolpath collect(LayerSource& source) {
  std::vector<Layer> layers;
  const std::size_t n = source.layer_count();
  layers.reserve(n);
  for (std::size_t k = 0; k < n; ++k) layers.push_back(source.layer(k));
  Toolpath t = source.record;  // after the layers: a source may complete it with the last
  t.layers = std::move(layers);
  return t;
}

ToolpathLayers::ToolpathLayers(Toolpath t) : layers_(std::move(t.layers)) {
  t.layers.clear();
  record = std::move(t);
}

RepeatedLayers::RepeatedLayers(std::vector<std::vector<Stroke>> designs, std::size_t layers,
                               double layer_height_mm)
    : designs_(std::move(designs)), layers_(designs_.empty() ? 0 : layers), layer_height_mm_(layer_height_mm) {}

Layer RepeatedLayers::layer(std::size_t index) {
  return {static_cast<double>(index + 1) * layer_height_mm_, layer_height_mm_, designs_[index % designs_.size()]};
}

}  // namespace strand::slicer
