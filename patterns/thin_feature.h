// Thin features of a sliced layer printed as single centre-line beads (medial-axis beads, as
// PrusaSlicer's thin walls) instead of being left out: strips no bead centred half a nozzle
// inside the boundary reaches, and parts narrower than two beads everywhere.
#pragma once

#include <vector>

#include "slicer/region.h"
#include "slicer/toolpath.h"

namespace strand::patterns {

struct ThinFeatures {
  // The layer without the strips the beads print: what perimeters and pattern fill. Equal to
  // the layer when no bead was found.
  slicer::Region fill_region;
  std::vector<slicer::Stroke> beads;  // one centre line each, nozzle wide, Feature::Wall
  double length_mm = 0.0;             // the beads' total length
};

// Centre-line beads of `layer` (nozzle d): the medial axis where the local width is in
// [d/2, 2 d], of every strip no bead centred d/2 inside reaches and of every part no disc of
// diameter 2 d fits in; spurs into corners pruned, ends that stop short of a free end
// stretched until the bead reaches it, every bead at least d long and at least d (centre to
// centre) from any bead of the fill, which lies within d/2 inside fill_region's boundary.
// Narrower strips stay in fill_region (the wall check then lists them as skipped).
ThinFeatures thin_features(const slicer::Region& layer, double nozzle_mm, double layer_height_mm);

struct PartThinBeads {
  std::vector<std::vector<slicer::Stroke>> per_layer;  // beside layer k's fill
  int count = 0;
  double length_mm = 0.0;
};
// thin_features on every layer of a part: each layer becomes its fill region.
PartThinBeads print_thin_features(std::vector<slicer::Region>& layers, double nozzle_mm,
                                  double layer_height_mm);

}  // namespace strand::patterns
