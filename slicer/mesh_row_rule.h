// The one rule for where a pose row on a robot-held mesh (mesh_substrate.h) may be, shared by
// the planner (postprocess/plan/mesh_pose_planner.h), which places rows by it and refuses a
// program that breaks it, and `strand check` on a pose CSV (postprocess/inspect/
// mesh_pose_check.h), which reads rows back by it. A row is its contact point p and normal n:
//
// - Its foot is where the line through p along n meets the mesh (the hit nearest p below it);
//   its offset is the distance from the foot to p along n.
// - Its normal is the mesh's area-weighted vertex normals interpolated at its foot (within
//   kMeshNormalDeg): the normal faces the nozzle where the mesh faces it.
// - Layer k's offset surface is the set of points (k + 1) h from the faceted mesh. A deposit's
//   contact is that far from the mesh within kMeshSurfaceMm; a travel is at least that far
//   less kMeshSurfaceMm, and above it along its normal.
// - Rows are placed from their foot S(u, v) and its normal N: p = S + t N with the smallest
//   t >= the layer's offset at which p is the offset from the mesh (t > the offset only where
//   the faceted mesh is concave under the nozzle).
// - A pass restart writes: the last point raised by `lift` along its normal (same foot, same
//   normal), the same contact point and normal turned about the nozzle axis (turn in place),
//   and the last point again (return).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "slicer/mesh_substrate.h"
#include "slicer/pose_program.h"

namespace strand::slicer {

// A deposit's contact may be this far from its layer's offset surface, mm, and a row's normal
// this far from the interpolated normal at its foot, deg.
inline constexpr double kMeshSurfaceMm = 0.05;
inline constexpr double kMeshNormalDeg = 1.0;

// The frame of a row at pattern point uv, `offset_mm` from the mesh (the planner's rows):
// normal and tangents those of the foot, the contact raised along the normal where the mesh is
// concave (see above). Precondition: s.in_domain(uv).
SurfaceFrame mesh_row_frame(const MeshSubstrate& s, const Vec2& uv, double offset_mm);

// A row read back by the rule.
struct MeshRowReading {
  bool over_mesh = false;       // the line along its normal meets the mesh
  Vec2 uv_mm = Vec2::Zero();    // pattern coordinates of its foot
  double along_mm = 0.0;        // foot -> contact along the normal (negative below the mesh)
  double clearance_mm = 0.0;    // contact -> the mesh's nearest point
  double normal_off_deg = 0.0;  // row normal vs the interpolated normal at the foot
};
MeshRowReading read_mesh_row(const MeshSubstrate& s, const Vec3& contact_mm, const Vec3& normal);

// Rows that break the rule, each with the line `strand check` prints for it.
struct MeshRowFault {
  std::size_t row = 0;
  std::string what;
};
struct MeshRowJudgement {
  std::vector<MeshRowFault> normals, off_surface;
  // The deposit farthest from its layer's offset surface: |clearance - offset| and its row.
  double worst_deposit_mm = 0.0;
  std::size_t worst_deposit_row = 0;
  bool ok() const { return normals.empty() && off_surface.empty(); }
};
// `at[i]` read from `rows[i]`; `layer_offsets_mm[k]` is layer k's offset (rows of later layers
// are judged against the last one).
MeshRowJudgement judge_mesh_rows(const std::vector<PosePoint>& rows,
                                 const std::vector<MeshRowReading>& at,
                                 const std::vector<double>& layer_offsets_mm);

}  // namespace strand::slicer
