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
// the link would cross or touch any stroke away from its own two ends. A loop no end took is
// spliced into the middle of a strand that runs beside it (within 1.05 gap, along a straight
// stretch): two side-by-side links a gap apart, the strand and the loop each opened for a gap
// between them. Returns the strands with their loops, then the loops left over, two joined
// into one stroke where they lie
// within 2 gaps of each other and a straight link between them meets nothing else (a neck
// between holes, or a hole and the outside, that the pattern does not fill). Deterministic.
std::vector<slicer::Stroke> splice_loops(std::vector<slicer::Stroke> loops,
                                         std::vector<slicer::Stroke> strands, double gap_mm,
                                         const std::vector<slicer::Stroke>& others);

}  // namespace strand::patterns
