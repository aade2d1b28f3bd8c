// Filling a sliced part: per layer, perimeter passes along the region's boundary, then the
// pattern clipped to what is left and joined into as few non-crossing strands as the
// region allows; the layers together make the part's Toolpath.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "patterns/region_pattern.h"
#include "slicer/layer_source.h"
#include "slicer/progress_listener.h"
#include "slicer/region.h"
#include "slicer/toolpath.h"

namespace strand::patterns {

struct LayerFill {
  // Outer perimeter levels, then the pattern strands with the innermost perimeter loops
  // spliced into them where a strand ends beside one (patterns/perimeter_splice.h), then
  // the loops left over. A scaffold layer over the strand bound (1 per region + 1 per hole)
  // gets seams down its dead-end lobes, or a narrow lobe printed round its edge, where they
  // save strands (patterns/lobe_seams.h), then
  // leaves out lone stubs shorter than four nozzles in a region still over it.
  std::vector<slicer::Stroke> strokes;
  int regions = 0;                 // connected parts of the layer's region
  int pattern_strands = 0;         // strands of the pattern (perimeters excluded)
  double pattern_length_mm = 0.0;  // pattern pieces alone, joins excluded
};

// `beads`: thin features' centre lines (patterns/thin_feature.h), printed as they are after
// the strands, or on a layer over the bound joined with them through the perimeter loops.
LayerFill fill_layer(const slicer::Region& region, const RegionPattern& p, int layer,
                     int perimeters, const slicer::Vec2& half_extent_mm,
                     const std::vector<slicer::Stroke>& beads = {});

struct PartFill {
  std::vector<slicer::Region> layers;  // layer k's region, layer k at z = (k + 1) h
  slicer::Vec2 half_extent_mm = slicer::Vec2::Zero();
  double volume_mm3 = 0.0;  // the part's volume, for the deposited porosity
  int perimeters = 0;
  // Per layer, beads printed as they are beside the fill (thin features' centre lines,
  // patterns/thin_feature.h); shorter than `layers` or empty: none.
  std::vector<std::vector<slicer::Stroke>> extra_strokes;
  slicer::Progress* progress = nullptr;  // told each filled layer (steps of the current phase)
};

// The part's toolpath (generator "slice"); derived: layers, regions and pattern strands per
// layer, deposited porosity inside the part, the pattern's own porosity. Throws InputError
// when the nozzle is wider than the part's wall somewhere: more than 4 nozzle^2 of a layer
// that no bead reaches, where the layers below and above also cover it (so the thin rim
// at the top or bottom of a curved part is not a wall), naming where.
slicer::Toolpath fill_part(const PartFill& part, const RegionPattern& p);
// part_fill_layers' layers in two steps, so many layers can be filled at once: fill(k), the
// costly part (wall check, perimeters, clipped and joined pattern), is const and may run for
// any layers in any order on several threads; layer_from(k, fill) then orders the strokes
// from where layer k - 1 ended and adds its sums, in order k = 0, 1, ... layer(k) is both.
class PartFillSource : public slicer::LayerSource {
 public:
  // Throws InputError where the nozzle is wider than the part's wall (see fill_part).
  virtual LayerFill fill(std::size_t k) const = 0;
  virtual slicer::Layer layer_from(std::size_t k, LayerFill fill) = 0;
  virtual const slicer::Region& region(std::size_t k) const = 0;  // layer k's sliced region
  slicer::Layer layer(std::size_t k) override { return layer_from(k, fill(k)); }
};

// The same one layer at a time: the record names the generator at once; its derived sizes
// (keys already there are kept) are complete once the last layer has been made.
std::unique_ptr<PartFillSource> part_fill_layers(PartFill part, RegionPattern p);

}  // namespace strand::patterns
