// Estimates from a MotionProgram: lengths, ink volume, strands and time per layer.
#pragma once

#include <vector>

#include "slicer/motion.h"

namespace strand::post {

struct LayerEstimate {
  int layer = 0;
  double z_mm = 0.0;
  int strands = 0;               // uninterrupted deposit runs
  double deposit_length_mm = 0.0;
  double travel_length_mm = 0.0;
  double volume_mm3 = 0.0;
  double time_naive_s = 0.0;     // distance / feed
};

struct Estimate {
  std::vector<LayerEstimate> layers;
  double deposit_length_mm = 0.0;
  double travel_length_mm = 0.0;
  double volume_mm3 = 0.0;
  double time_naive_s = 0.0;     // sum of distance / feed, dwells included
};

// Length of a move from `from` (arcs measured along the arc), mm.
double move_length(const slicer::Vec3& from, const slicer::Move& mv);
Estimate estimate(const slicer::MotionProgram& program);

}  // namespace strand::post
