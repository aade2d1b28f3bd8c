// Arc segmentation for firmware without G2/G3: chords whose sagitta stays within a bound.
#pragma once

#include <vector>

#include "slicer/geometry.h"

namespace strand::post {

using slicer::Vec2;

// Points after `from` (excluded) up to `to` (included) along the arc around `center`, with
// equal chords none of which is farther than `chord_tolerance_mm` from the arc.
// Precondition: chord_tolerance_mm > 0 and |from - center| == |to - center| (within rounding).
std::vector<Vec2> segment_arc(const Vec2& from, const Vec2& center, const Vec2& to, bool ccw,
                              double chord_tolerance_mm);

// Number of equal chords needed for a sweep of `sweep_rad` on `radius_mm`.
int chords_needed(double radius_mm, double sweep_rad, double chord_tolerance_mm);

}  // namespace strand::post
