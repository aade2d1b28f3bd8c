// Start tours for pen-stroke ordering, improved afterwards by 2-opt and Or-opt. Greedy: the
// shortest candidate gaps are taken first to chain strokes end to end, then the chains are
// visited nearest-first from the start point; on large random drawings it starts (and ends)
// shorter than the nearest-neighbour walk, which strands strokes that only reversals of half
// the tour bring back.
#pragma once

#include <vector>

#include "postprocess/plot/near_lists.h"
#include "slicer/geometry.h"

namespace strand::post {

// Strokes in drawing order; reversed[s] is set when stroke s is entered by its end
// (ends[2s + 1]). Deterministic: gaps taken by length, ties in candidate-list order.
std::vector<int> greedy_order(const std::vector<slicer::Vec2>& ends, const slicer::Vec2& start,
                              const NearLists& near, std::vector<char>& reversed);

// The nearest-neighbour walk from start: each next stroke the one with the nearest free
// endpoint (ties by index), reversed[s] as for greedy_order.
std::vector<int> nearest_neighbour_order(const std::vector<slicer::Vec2>& ends,
                                         const slicer::Vec2& start, std::vector<char>& reversed);

}  // namespace strand::post
