// A design's pattern over a region instead of a specimen: the generator's own parameter
// table minus the rows that set a specimen's extent (the part's shape does), and the
// pattern's lines for one layer on a grid fixed in the part frame, so lines and nodes
// stack the same way in every layer.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "patterns/region_clip.h"
#include "patterns/registry.h"

namespace strand::patterns {

struct RegionPattern {
  std::string name;       // generator name: scaffold, tetrachiral, ...
  nlohmann::json values;  // the pattern's checked values, defaults filled, no extent rows
  double nozzle_mm = 0.0;
  double layer_height_mm = 0.0;
  double speed_mm_per_min = 0.0;
  double pitch_mm = 0.0;             // scaffold: line spacing
  std::vector<double> angles_deg;    // scaffold: lay-down angle per layer (cycled)
  std::vector<PatternLine> lattice;  // lattices: one layer's strands, part frame
  slicer::Feature connector = slicer::Feature::Infill;  // boundary joins
  // Pieces of the pattern shorter than this inside a region are left out: a scaffold line
  // grazing a corner (1 nozzle), a lattice node or rib cut by the boundary (4 nozzles),
  // which would each become a strand of its own, mm.
  double min_piece_mm = 0.0;
  // Porosity of the unbounded pattern: scaffold 1 - A / (pitch h); lattices from the
  // generated layer's strand length over the central half of the lattice.
  double porosity = 0.0;
};

// Flags of `generator` that set a specimen's extent or border and make no sense for a
// region: size, rows, cols, height, layers, overhang, grip.
bool is_extent_key(const std::string& key);
// Checks `given` (CLI flags or job keys of the generator's table, extent keys excluded)
// and builds the pattern over the part's xy half extents (the part frame is centred on the
// pattern grid's origin). Throws InputError naming every problem.
RegionPattern region_pattern(const GeneratorSpec& generator, const nlohmann::json& given,
                             const slicer::Vec2& half_extent_mm);
// The pattern's lines for `layer` covering the box [-half, half] (plus a margin).
std::vector<PatternLine> pattern_lines(const RegionPattern& p, int layer,
                                       const slicer::Vec2& half_extent_mm);

}  // namespace strand::patterns
