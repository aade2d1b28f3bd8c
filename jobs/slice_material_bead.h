// A layer with material that its fill leaves empty: the top of a rounded part (beast.obj's
// last layer at 30 mm, nozzle 0.6) is a blob between half a bead and one bead wide, too narrow
// for a perimeter (centred half a bead inside) or any pattern piece, and not a wall (nothing
// covers it above), so nothing was written there. It gets a centre bead instead.
#pragma once

#include <vector>

#include "slicer/region.h"
#include "slicer/toolpath.h"

namespace strand::jobs {

// One bead per part of `region` at least half a bead wide (the part shrunk by a quarter
// bead is not empty): along the shrunk part's boundary from its lowest to its highest point
// along the part's long axis, within a quarter bead of the centre line for such narrow parts.
std::vector<slicer::Stroke> material_beads(const slicer::Region& region, double nozzle_mm,
                                           double layer_height_mm);

}  // namespace strand::jobs
