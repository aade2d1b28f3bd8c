// Sampling flat (u, v) segments on a curved surface: lines and arcs stay exact in the
// pattern, and are cut only here, where the chord between consecutive mapped points must stay
// within the chord tolerance of the mapped curve ON THE SURFACE (a straight line in (u, v) is
// a helix on a cylinder, so it is cut too).
#pragma once

#include <cstddef>
#include <vector>

#include "slicer/surface.h"
#include "slicer/toolpath.h"

namespace strand::post {

using slicer::Vec2;

// Pattern points after `from` (excluded) up to the segment's end (included) such that every
// chord between the mapped points, at nozzle offset `offset_mm`, deviates from the mapped
// curve by at most `tolerance_mm`. Precondition: tolerance_mm > 0.
std::vector<Vec2> sample_on_surface(const slicer::Surface& surface, const Vec2& from,
                                    const slicer::Segment& segment, double offset_mm,
                                    double tolerance_mm);

// An upper bound of the points sample_on_surface returns (for bounding work before doing
// it): the chord count of the tightest curvature the mapped segment can have.
std::size_t sample_bound(const slicer::Surface& surface, const Vec2& from,
                         const slicer::Segment& segment, double offset_mm, double tolerance_mm);

}  // namespace strand::post
