// Checks for toolpaths wrapped round a cylinder (`--wrap full`), judged on the cylinder's
// topology: x is the arc length round it, taken modulo the period, so a strand may run on
// past the seam and meets copies of itself one period away.
#pragma once

#include <utility>
#include <vector>

#include "slicer/toolpath.h"

namespace strand::testing {

// The segments of one stroke as drawn (unwrapped x), arcs as chords within `tol_mm`.
std::vector<std::pair<slicer::Vec2, slicer::Vec2>> flat_segments(const slicer::Stroke& s,
                                                                 double tol_mm);

// Proper crossings inside one layer on the cylinder: every segment against every other one
// and its copies shifted by k * period (|k| <= 2; each segment spans less than a period).
// Returns the crossing points, x wrapped into [-period / 2, period / 2).
std::vector<slicer::Vec2> wrapped_crossings(const slicer::Layer& layer, double period_mm);

// The stroke wrapped onto one period: cut where it crosses the seam x = +-period / 2 into
// pieces whose points lie in [-period / 2, period / 2].
std::vector<std::vector<slicer::Vec2>> seam_pieces(const slicer::Stroke& s, double period_mm);

// Largest distance on the cylinder between the end of a seam piece and the start of the next
// (0 for a continuous strand); the seam's two sides are the same line.
double largest_seam_gap(const std::vector<std::vector<slicer::Vec2>>& pieces, double period_mm);

// Smallest centre-line distance on the cylinder between segments of one layer that do not
// share an end point (x modulo the period): below the nozzle, beads not joined would overlap.
double wrapped_min_gap(const slicer::Layer& layer, double period_mm);

// Every layer one stroke; no crossing modulo the period; no segment spanning half the period
// or more along x (so each maps unambiguously); the stroke's seam pieces meet within 1e-6 mm;
// derived cells_around * cell_around_mm = wrap_period_mm = period.
void expect_sound_wrap(const slicer::Toolpath& t, double period_mm);

}  // namespace strand::testing
