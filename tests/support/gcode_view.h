// Test helpers that look at parsed G-code the way a reviewer would: per-layer deposit
// segments, bounds, and the long straight filaments of a layer.
#pragma once

#include <vector>

#include "postprocess/inspect/gcode_parser.h"

namespace strand::testing {

struct DepositSeg {
  slicer::Vec3 a, b;
  slicer::Feature feature;
  int layer;
};

// Straight deposit moves (arcs excluded) with their start points.
std::vector<DepositSeg> deposit_segments(const slicer::MotionProgram& p);

}  // namespace strand::testing
