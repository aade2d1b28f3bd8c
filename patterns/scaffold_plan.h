// What each layer of a log-pile lays (patterns/scaffold.h): its angle, line spacing, half-pitch
// shift, speed and bead, from the angle cycle, a z grade, --stagger and a job's schedule.
#pragma once

#include <vector>

#include "patterns/scaffold.h"

namespace strand::patterns {

struct LayerPlan {
  double angle_deg = 0.0;
  double pitch_mm = 0.0;    // centre to centre where the gap is not graded along x or y
  bool staggered = false;   // lines between those of the unshifted layer
  double speed_mm_per_min = 0.0;
  double flow = 1.0;        // bead section relative to a nozzle-wide bead
  double width_mm = 0.0;    // bead width giving that section at the layer height
};

// One plan per layer. Layer k takes angle k of the cycle, the gap of a z grade at its bottom
// (fraction k / layers), then its schedule entry's values. A layer is staggered when as many
// earlier layers ran in its direction (mod 180 deg) as make it the second, fourth, ... one.
std::vector<LayerPlan> scaffold_layer_plans(const ScaffoldParams& p);

// The bead width whose section (slicer::bead_area_mm2) is `flow` times a nozzle-wide bead's.
double flow_width_mm(double nozzle_mm, double layer_height_mm, double flow);

}  // namespace strand::patterns
