// Self-crossings and touches of strands on a cylinder, judged in pattern coordinates (u around,
// v along the axis) with u periodic: segments are cut at the seam u = 0 = circumference, so a
// strand that runs across the seam is compared with what lies on the other side.
#pragma once

#include <vector>

#include "postprocess/inspect/crossings.h"

namespace strand::post {

struct CylinderStrandPoint {
  slicer::Vec2 uv_mm = slicer::Vec2::Zero();  // u unwrapped along the strand
  std::size_t source = 0;                     // row or move this point came from
};

struct CylinderLayer {
  int layer = 0;
  double circumference_mm = 0.0;  // period of u
  std::vector<std::vector<CylinderStrandPoint>> strands;
};

// Contacts per layer; at_mm holds (u in [0, circumference), v); move_a/move_b are the sources
// of the segments' end points. Segments closer than `touch_mm` touch (not across the seam).
ContactReport find_cylinder_contacts(const std::vector<CylinderLayer>& layers, double touch_mm);

}  // namespace strand::post
