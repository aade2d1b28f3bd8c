// Planning on a cylinder: a Toolpath already placed in pattern coordinates (u around, v
// along the axis) -> one timed PoseProgram. Layer k is printed with the nozzle tip at offset
// z_k = (k + 1) h above the substrate; deposits are cut so chords stay within the arc
// tolerance on the surface; travels back the substrate off the nozzle, turn, and approach.
#pragma once

#include <cstddef>
#include <map>

#include "machines/workpiece_pose.h"
#include "slicer/cylinder_surface.h"
#include "slicer/pose_program.h"
#include "slicer/toolpath.h"

namespace strand::post {

// Bound on the poses of one program (about 200 bytes each): a job that would need more is
// refused before it is planned (raise --arc-tolerance or print fewer layers).
inline constexpr std::size_t kMaxPosePoints = 2'000'000;

struct PosePlanOptions {
  double arc_tolerance_mm = 0.01;                            // chord error on the surface
  std::map<slicer::Feature, double> deposit_speed_mm_per_s;  // contact speed per feature
  double default_deposit_speed_mm_per_s = 6.0;               // features not in the map
  double travel_speed_mm_per_s = 20.0;
  double lift_speed_mm_per_s = 10.0;  // backing off and approaching
  double lift_mm = 3.0;               // extra offset for travels
};

// Plans every layer of `t` (strokes in (u, v), z_mm = nozzle tip offset). Laps are assigned
// (laps.h). Throws InputError naming arc-tolerance when the program would exceed
// kMaxPosePoints.
slicer::PoseProgram plan_poses(const slicer::Toolpath& t, const slicer::CylinderSurface& s,
                               const machines::Holder& holder, const PosePlanOptions& options);

}  // namespace strand::post
