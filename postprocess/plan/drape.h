// Conformal printing on a 3-axis machine: a flat toolpath draped over a substrate Surface
// with the nozzle kept vertical. Pattern point (u, v) goes to the surface point there,
// raised by the layer's z; travels rise above the whole substrate. Where the substrate is
// steeper than the machine's max_surface_slope_deg the nozzle's side would touch it, so
// such a path is refused.
#pragma once

#include "machines/profile.h"
#include "postprocess/plan/planner.h"
#include "slicer/motion.h"
#include "slicer/surface.h"
#include "slicer/toolpath.h"

namespace strand::post {

// Deposits are cut into pieces no longer than this before mapping, so the path follows
// the surface between mesh triangles, mm.
inline constexpr double kDrapeStepMm = 0.5;

// Plans `t` flat (arcs as chords), then maps every point through `s`. The pattern frame's
// origin is the surface's (u, v) origin; the machine's part centre offsets x and y as for
// flat parts. Throws InputError where the path leaves the substrate, where the slope under
// it exceeds the machine's limit (naming the slope and the point), and when the result
// leaves the build volume.
slicer::MotionProgram plan_draped(const slicer::Toolpath& t, const slicer::Surface& s,
                                  const machines::MachineProfile& machine,
                                  const PlanOptions& options);

}  // namespace strand::post
