// Filling closed outlines for pen plotters, with Clipper: parallel hatch lines clipped to the
// region the fill rule defines, or concentric rings offset inwards (the polar plotter's fill).
// Holes are respected by both.
#pragma once

#include <string>
#include <vector>

#include "slicer/curves.h"

namespace strand::post {

enum class FillStyle {
  Hatch,       // parallel lines + the region's outline (default)
  Concentric,  // inward offset rings + the region's outline
  Outline,     // the outline only
  None,        // filled areas are not drawn (only stroked paths are)
};
// Throws InputError naming plot.fill for an unknown name.
FillStyle fill_style_from_string(const std::string& name);
std::string to_string(FillStyle s);

// Hatch or ring lines a fill may draw per shape; more means a spacing far too fine for the
// shape (the fill would take hours and the file gigabytes), refused before any work.
inline constexpr double kMaxFillLines = 20000;

// Hatch lines `spacing_mm` apart at `angle_deg` inside the closed polylines `outlines`
// (even-odd or non-zero rule). Each returned polyline is one pen-down line. Throws
// InputError when the spacing would need more than kMaxFillLines lines, for a coordinate
// beyond kMaxCoordinateMm, and for anything Clipper refuses.
std::vector<slicer::Polyline> hatch_fill(const std::vector<slicer::Polyline>& outlines,
                                         bool evenodd, double spacing_mm, double angle_deg);

// Rings `spacing_mm` apart inside the region (the first one spacing_mm inside its border),
// each a closed polyline (last point = first). Rings of one region never cross each other
// or the border; holes get rings around them. Throws InputError like hatch_fill.
std::vector<slicer::Polyline> concentric_fill(const std::vector<slicer::Polyline>& outlines,
                                              bool evenodd, double spacing_mm);

// Upper bound on the points `style` adds for these outlines, without clipping: hatch
// segments end where hatch lines cross outline edges (an edge spanning h across the lines
// crosses at most h / spacing + 1 of them); rings have at most twice the outline's vertices
// plus 64 round-join points each; the outline itself counts once.
double fill_point_bound(const std::vector<slicer::Polyline>& outlines, FillStyle style,
                        double spacing_mm, double angle_deg);

// The border of the filled region as closed polylines: the outlines themselves, closed.
std::vector<slicer::Polyline> fill_outline(const std::vector<slicer::Polyline>& outlines);

}  // namespace strand::post
