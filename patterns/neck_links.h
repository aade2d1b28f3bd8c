// Strands joined straight across a neck. Where a part narrows to under three beads, the fill
// boundary (a bead and a half inside a perimeter) splits in two and the pattern's strands end
// on either side of the neck, a bead or two apart; the perimeter loop cannot join them (each
// end lies beside a different stretch of it). A straight link from one end to the other, kept
// clear of every other bead and inside the part's edge, makes them one strand. The same joins
// the pieces of a fin's flat perimeter where the fin narrows under a bead.
#pragma once

#include <cstddef>
#include <vector>

#include "slicer/region.h"
#include "slicer/toolpath.h"

namespace strand::patterns {

struct NeckLinkOptions {
  double reach_mm = 0.0;      // the longest link
  double clearance_mm = 0.0;  // from every other bead's centre line
  double edge_mm = 0.0;       // from the part's edge
  std::size_t from = 0;       // a link joins at least one strand at or after this index
};

// `strands` with pairs of ends of different strands joined by straight links, shortest first,
// where the link stays `clearance_mm` from every segment of `strands` and `others` (but the
// two it joins, at its ends) and inside `region` by `edge_mm`; chains never close. The links are
// `Feature::Wall` where both strands end in a wall, else the first strand's end feature.
// Deterministic; strands no link joins are returned unchanged, in their order.
std::vector<slicer::Stroke> link_across_necks(std::vector<slicer::Stroke> strands,
                                              const std::vector<slicer::Stroke>& others,
                                              const slicer::Region& region,
                                              const NeckLinkOptions& options);

}  // namespace strand::patterns
