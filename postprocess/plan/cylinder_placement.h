// Where a flat pattern sits on the cylinder: pattern x -> u around (arc length), y -> v along
// the axis. A patch is centred on u = 0 (the line that faces the nozzle at turn 0) and on the
// cylinder's mid-length; a full wrap keeps its periodic x and is centred along the axis.
#pragma once

#include "slicer/cylinder_surface.h"
#include "slicer/substrate_params.h"
#include "slicer/toolpath.h"

namespace strand::post {

// Shifts the toolpath into pattern coordinates on `cylinder` and checks it fits: a patch no
// wider than the circumference where u is measured, any pattern no longer than the cylinder
// (bead included). Throws InputError naming substrate.wrap / substrate.length and the limit.
slicer::Toolpath place_on_cylinder(const slicer::Toolpath& t, const slicer::SubstrateSpec& s,
                                   const slicer::CylinderSurface& cylinder);

// The sentence reports and headers use to say where the pattern sits.
std::string placement_text(const slicer::SubstrateSpec& s);

}  // namespace strand::post
