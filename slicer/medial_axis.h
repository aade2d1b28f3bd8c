// Centre lines of a region's narrow parts: its medial axis (Boost.Polygon's segment Voronoi
// diagram), kept where the local width lies in a band, with the spurs to the corners pruned
// and the rest chained into polylines.
#pragma once

#include <cstddef>
#include <vector>

#include "slicer/region.h"

namespace strand::slicer {

struct CentreLine {
  std::vector<Vec2> points;      // open, or closed when front() == back()
  std::vector<double> width_mm;  // local width at each point: twice the distance to the boundary
  bool operator==(const CentreLine&) const = default;
};

struct MedialAxisLimits {
  double min_width_mm = 0.0;  // narrower places are left out (a tip, a corner)
  double max_width_mm = 0.0;  // wider places are left out (the thick part beside a rib)
  double min_length_mm = 0.0; // shorter centre lines are left out
  // Boundary segments of one call at most: a larger region returns no centre line (the work
  // of the diagram stays bounded; callers pass the narrow strips, not whole layers).
  std::size_t max_segments = 20000;
};

// The medial axis of `region` where its local width lies in [min_width_mm, max_width_mm],
// without branches that run into a corner (a branch from a free end to a fork, shorter than
// the width at the fork), chained through forks along the straightest continuation, every
// line at least min_length_mm long and longer than its widest place (a corner's bisector cut
// out by the band is not a feature). Deterministic: the same region gives the same lines.
std::vector<CentreLine> centre_lines(const Region& region, const MedialAxisLimits& limits);

double polyline_length_mm(const std::vector<Vec2>& points);

}  // namespace strand::slicer
