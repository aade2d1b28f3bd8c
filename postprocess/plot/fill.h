// Filling closed outlines for pen plotters: parallel hatch lines clipped to the region the
// fill rule defines (holes respected), using Clipper.
#pragma once

#include <vector>

#include "slicer/curves.h"

namespace strand::post {

// Hatch lines `spacing_mm` apart at `angle_deg` inside the closed polylines `outlines`
// (even-odd or non-zero rule). Each returned polyline is one pen-down line.
std::vector<slicer::Polyline> hatch_fill(const std::vector<slicer::Polyline>& outlines,
                                         bool evenodd, double spacing_mm, double angle_deg);

}  // namespace strand::post
