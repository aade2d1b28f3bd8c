// Laps: a layer on a turning substrate is printed as runs that turn the workpiece one way
// (forward) and then back (return), as the thesis printed its cylinder, so the holder's last
// joint never winds up. A lap runs from its start to the last point where it reaches its
// farthest turn in its direction; the next lap turns back.
#pragma once

#include <vector>

#include "slicer/pose_program.h"

namespace strand::post {

// Splits points [first, last] (one layer, turn_rad set) into laps; direction +1 for the
// first lap when the layer reaches farther above its start turn than below it.
std::vector<slicer::PoseLap> split_laps(const std::vector<slicer::PosePoint>& points,
                                        std::size_t first, std::size_t last, int layer);

// Assigns laps to every layer of `program` (points carry their layer) and numbers each
// point's lap globally.
void assign_laps(slicer::PoseProgram& program);

// The turning range over the whole program, rad: {min, max}.
std::pair<double, double> turn_range(const slicer::PoseProgram& program);

}  // namespace strand::post
