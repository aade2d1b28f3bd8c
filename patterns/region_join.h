// Joining clipped pattern pieces into as few strands as possible without a crossing: two
// pieces whose ends are neighbours along a boundary ring are joined by the stretch of ring
// between them, as the log-pile scaffold joins its lines by U-turns. No other piece ends
// on that stretch and pieces lie inside the ring set, so a join never crosses anything.
#pragma once

#include <vector>

#include "patterns/region_clip.h"
#include "slicer/toolpath.h"

namespace strand::patterns {

struct JoinOptions {
  slicer::Feature connector = slicer::Feature::Infill;  // feature of the ring stretches
  double width_mm = 0.0;                                // stroke bead width
  double height_mm = 0.0;                               // stroke bead height
};

// Strands made of every piece once. First each strand grows piece by piece to a free ring
// neighbour of its end (pieces taken in their `order`, the scaffold's line order, so
// convex regions come out as one serpentine); then strand ends that are ring neighbours
// are joined, shortest stretch first, and exchanges free ends that can then be joined.
// Twenty-four growth variants (order either way, started at 0, 1/4, 1/2 or 3/4 of it; the
// nearer neighbour, always forward or always backward along the ring) are tried and the
// fewest strands kept, then the least ring deposited. Then a local search
// (patterns/join_search.h) moves strand ends round the rings until no two strands can merge
// and, with `loops` (the innermost perimeter loops, for patterns/perimeter_splice.h), until no
// loop beside which no strand ends can get one. Deterministic.
std::vector<slicer::Stroke> join_pieces(const RingSet& rs, const std::vector<FillPiece>& pieces,
                                        const JoinOptions& options,
                                        const std::vector<slicer::Stroke>& loops = {});

}  // namespace strand::patterns
