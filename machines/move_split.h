// Cutting one move (line or arc) into pieces: for valve lag and for firmware limits on E
// per move. Deposit volume is shared in proportion to length.
#pragma once

#include <vector>

#include "slicer/motion.h"

namespace strand::machines {

// The point a fraction t in [0, 1] of the way along `mv` starting at `from` (arcs along the
// arc, z linear).
slicer::Vec3 point_along(const slicer::Vec3& from, const slicer::Move& mv, double t);

// `mv` from `from` cut at the fractions `cuts` (strictly increasing, in (0, 1)): cuts.size()+1
// moves of the same kind, feed and feature, whose volumes sum to mv.volume_mm3.
std::vector<slicer::Move> split_move(const slicer::Vec3& from, const slicer::Move& mv,
                                     const std::vector<double>& cuts);

// Length of a move from `from`, arcs along the arc, mm.
double path_length(const slicer::Vec3& from, const slicer::Move& mv);

}  // namespace strand::machines
