// Graded log-piles: where the filaments of a layer go when the gap varies along x or y
// (patterns/scaffold.h, GapGrade), and the footprint side such a grade fills.
#pragma once

#include <vector>

#include "patterns/scaffold.h"

namespace strand::patterns {

// Filament centres along a graded side, from its low edge: the first at nozzle / 2, each
// next one a nozzle plus the grade's gap (at the gap's start, as a fraction of `length_mm`)
// further; as many (>= 2) as bring the side, edge to edge, nearest to `length_mm`.
std::vector<double> graded_centres_mm(const GapGrade& grade, double nozzle_mm, double length_mm);

// Offsets along a layer's normal n of its graded lines. `n_axis` = n . grade axis (not 0);
// `side_mm` is the footprint's side along the axis, `length_mm` the graded length (the
// requested side), `reach_mm` how far from the centre a line may lie. The lines cross the
// footprint's centre line along the axis where a perpendicular layer would put them, with
// the gaps measured across the lines; past the ends the end values hold. Sorted ascending.
std::vector<double> graded_offsets_mm(const GapGrade& grade, double nozzle_mm, double n_axis,
                                      double side_mm, double length_mm, double reach_mm);

}  // namespace strand::patterns
