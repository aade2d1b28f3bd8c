// Pattern lines clipped to a region's rings, with each cut located on its ring (which ring,
// how far along it), so the pieces can be joined along the boundary afterwards.
#pragma once

#include <vector>

#include "slicer/region.h"
#include "slicer/toolpath.h"

namespace strand::patterns {

// A point on ring `ring` of a ring set: on edge `edge` (from vertex edge to edge + 1) at
// arc length `s_mm` from the ring's first vertex. ring = -1: not on a ring (an open end
// of the pattern inside the region).
struct RingSpot {
  int ring = -1;
  int edge = 0;
  double s_mm = 0.0;
  bool operator==(const RingSpot&) const = default;
};

// An open polyline of the pattern; features[i] is the feature of points[i] -> points[i + 1].
struct PatternLine {
  std::vector<slicer::Vec2> points;
  std::vector<slicer::Feature> features;
  int order = 0;  // where it lies in the pattern's own order (scaffold: line index)
  bool operator==(const PatternLine&) const = default;
};

struct FillPiece {
  PatternLine line;  // the part inside the region
  RingSpot start, end;
  bool operator==(const FillPiece&) const = default;
};

// Rings with their cumulative arc lengths, for locating and walking.
struct RingSet {
  std::vector<slicer::Ring> rings;
  std::vector<std::vector<double>> s_mm;  // s_mm[r][i]: arc length at vertex i; back() = total
};
RingSet ring_set(const std::vector<slicer::Ring>& rings);
slicer::Vec2 point_at(const RingSet& rs, const RingSpot& spot);
double ring_length_mm(const RingSet& rs, int ring);
// Arc length from spot a forward (increasing s) to spot b on the same ring, mm.
double ring_gap(const RingSet& rs, const RingSpot& a, const RingSpot& b);
// Ring points strictly between spots a and b walking forward (or backward), then b.
void walk_ring(const RingSet& rs, const RingSpot& a, const RingSpot& b, bool forward,
               std::vector<slicer::Vec2>& out);

// The parts of `lines` inside the region bounded by `rs` (even-odd). Points exactly on a
// ring count consistently on one side (simulation of simplicity), so every piece runs
// from one cut to the next. Uses a uniform grid over the ring edges.
std::vector<FillPiece> clip_to_rings(const RingSet& rs, const std::vector<PatternLine>& lines);

}  // namespace strand::patterns
