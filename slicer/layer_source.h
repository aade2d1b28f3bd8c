// A toolpath made one layer at a time: what lets a job of millions of moves run in memory
// independent of its size (generators yield layers, the planner and emitter take them as they
// come; postprocess/plan/produce.h). Toolpath stays the whole-part value for everything that
// wants all layers at once (previews, curved substrates, tests): collect() builds it.
#pragma once

#include <cstddef>
#include <memory>

#include "slicer/toolpath.h"

namespace strand::slicer {

class LayerSource {
 public:
  virtual ~LayerSource() = default;
  virtual std::size_t layer_count() const = 0;
  // Layer `index`; called once per index, in order 0, 1, ..., layer_count() - 1.
  virtual Layer layer(std::size_t index) = 0;

  // Generator and parameters, known before the first layer (planning reads them), and the
  // derived sizes, known before the first layer or at the latest once the last has been
  // made (a sliced part's porosity sums every layer). Its `layers` stays empty.
  Toolpath record;
};

// The record with every layer: the whole toolpath in memory.
Toolpath collect(LayerSource& source);

// Hands out the layers of a toolpath already built, each moved out as it is asked for.
class ToolpathLayers final : public LayerSource {
 public:
  explicit ToolpathLayers(Toolpath t);
  std::size_t layer_count() const override { return layers_.size(); }
  Layer layer(std::size_t index) override { return std::move(layers_.at(index)); }

 private:
  std::vector<Layer> layers_;
};

// `layers` copies of a few layer designs used in turn (layer k is designs[k % size]) at
// z = (k + 1) * layer_height_mm: the stacks of identical or alternating layers lattices are.
class RepeatedLayers final : public LayerSource {
 public:
  RepeatedLayers(std::vector<std::vector<Stroke>> designs, std::size_t layers, double layer_height_mm);
  std::size_t layer_count() const override { return layers_; }
  Layer layer(std::size_t index) override;

 private:
  std::vector<std::vector<Stroke>> designs_;
  std::size_t layers_;
  double layer_height_mm_;
};

}  // namespace strand::slicer
