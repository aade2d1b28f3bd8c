// Perimeter loops spliced into the pattern's strands, so a layer needs fewer strands: a
// strand that ends on the fill boundary, one nozzle inside a perimeter loop, runs round the
// whole loop through a short straight link.
#pragma once

#include <vector>

#include "slicer/toolpath.h"

namespace strand::patterns {

// `loops`: closed perimeter strokes (the innermost level); `strands`: the pattern's strands,
// whose ends lie on the fill boundary `gap_mm` inside the loops; `others`: every other
// stroke of the layer. Each strand end takes the loop nearest to it (within 1.05 gap) unless
// the link would cross or touch any stroke away from its own two ends. Returns the strands
// with their loops, then the loops left over. Deterministic.
std::vector<slicer::Stroke> splice_loops(std::vector<slicer::Stroke> loops,
                                         std::vector<slicer::Stroke> strands, double gap_mm,
                                         const std::vector<slicer::Stroke>& others);

}  // namespace strand::patterns
