// Contacts between deposited segments inside each layer: proper crossings (a filament
// over itself, which grows a bump layer after layer) and touches (end on a filament,
// collinear overlap). O(n log^2 n + k) per layer for n segments and k box overlaps.
#pragma once

#include <vector>

#include "slicer/motion.h"

namespace strand::post {

struct Contact {
  int layer = 0;
  slicer::Vec2 at_mm = slicer::Vec2::Zero();
  std::size_t move_a = 0;  // indices into MotionProgram::moves
  std::size_t move_b = 0;
};

struct ContactReport {
  std::vector<Contact> crossings;
  std::vector<Contact> touches;
};

// Arcs are flattened with `arc_tolerance_mm`; segments closer than `touch_mm` touch.
// Consecutive segments of one strand (sharing their joint) are not contacts.
ContactReport find_contacts(const slicer::MotionProgram& program, double arc_tolerance_mm,
                            double touch_mm);

}  // namespace strand::post
