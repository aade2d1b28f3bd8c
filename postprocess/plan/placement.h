// Placing a part on the machine and proving every move stays in the build volume.
#pragma once

#include "machines/profile.h"
#include "slicer/motion.h"

namespace strand::post {

// Throws InputError naming the machine, the failing dimension and the point when any move
// (travel included, arcs at their extremes) leaves the build volume.
void check_fits(const slicer::MotionProgram& program, const machines::MachineProfile& machine);

}  // namespace strand::post
