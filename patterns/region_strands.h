// Strands per connected part of a layer's region, against the bound a part allows (one, plus
// one per hole): what the fill aims at (patterns/region_fill.h) and the slice summary counts.
#pragma once

#include <vector>

#include "slicer/region.h"
#include "slicer/toolpath.h"

namespace strand::patterns {

struct RegionStrands {
  int strands = 0;  // extruding runs (perimeters included) whose deposit lies in the region
  int holes = 0;    // the region's holes
  bool operator==(const RegionStrands&) const = default;
};

// `region` as a bead sees it: opened by a quarter nozzle, so a neck or a wall narrower than
// half a bead (which no bead prints: the thin-feature rule) no longer joins two parts or
// closes a hole. The bound counts these parts and holes. `region` itself where the opening
// changes no part or hole.
slicer::Region bead_parts(const slicer::Region& region, double nozzle_mm);

// The part of `region` holding most of (at most 9) points spread along `points`; -1 when
// none holds any.
int part_holding(const slicer::Region& region, const std::vector<slicer::Vec2>& points);
// The same for the points one stroke deposits along (its start and every segment's end).
int part_holding(const slicer::Region& region, const slicer::Stroke& stroke);

// Per connected part of `region` (in its order): the strands of `strokes` printed there. A
// strand is a run of strokes each starting where the previous one ended (no travel between
// them: one strand in the file, as the estimate counts them); it belongs to the part that
// holds most of its points.
std::vector<RegionStrands> strands_per_region(const slicer::Region& region,
                                              const std::vector<slicer::Stroke>& strokes);

// Strands beyond the bound, summed over the parts.
int strands_over_bound(const std::vector<RegionStrands>& parts);

}  // namespace strand::patterns
