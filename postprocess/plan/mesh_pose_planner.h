// Planning on a robot-held mesh (slicer/mesh_substrate.h): a Toolpath placed in the mesh's
// pattern coordinates (u, v) -> one timed PoseProgram for a robot cell with a fixed nozzle.
//
// The path: layer k's nozzle tip (k + 1) h along the mesh's normal, deposits cut so chords
// stay within the arc tolerance on the offset surface, travels backed off along the normal,
// across at the raised offset and back down (as on a cylinder). Every point's nozzle cone
// (robot.nozzle_cone) is tested against the mesh: a touch is refused, naming the point.
//
// The orientation rule: the workpiece is posed so the local normal points against the nozzle
// axis and the contact point sits at the nozzle tip. Of the poses that do, each is the
// smallest rotation (tilt) from the reference pose (the mesh's facing against the nozzle, the
// flange axis along robot.substrate_axis as a cylinder's) that turns its normal against the
// nozzle, followed by one rotation about the nozzle axis kept for the whole pass. The pose is
// then a function of the normal alone: neighbouring points get neighbouring poses and the
// joints move continuously, and no rotation about the nozzle axis gathers as the path loops
// (the pose-to-pose smallest rotation would: around a node or a layer it comes back turned by
// the enclosed curvature, 27 deg a layer on the sample sphere cap). The first pass's rotation
// is tried 15 deg apart, each solved from the arm's start postures as a cylinder's first pose
// is; the one that presents the most following points wins (then the one nearest mid-range).
// Every pose is solved by inverse kinematics along the path (machines/robot_arm.h), each from
// the previous solution. Where a pose would leave a joint's range (less kMeshJointMarginDeg)
// or the reach, or move a joint more than 10 deg from the previous pose (a posture near a
// singular one), the pass ends: the workpiece backs off along the nozzle axis, turns about it
// in steps of at most 1 deg to the candidate rotation that presents the most following points,
// comes back, and a new pass (lap) starts. A point no rotation can present is refused.
#pragma once

#include <cstddef>
#include <vector>

#include "machines/holder_profile.h"
#include "postprocess/plan/pose_planner.h"
#include "slicer/mesh_substrate.h"
#include "slicer/pose_program.h"
#include "slicer/toolpath.h"

namespace strand::post {

// Candidate rotations about the nozzle axis for a first pose or a restarted pass, deg apart.
inline constexpr double kMeshRotationStepDeg = 15.0;
// Joints are kept this far inside their limits, and the wrist this far inside the reach, so
// a CSV rounded to its printed digits checks the same, deg and mm.
inline constexpr double kMeshJointMarginDeg = 0.5;
inline constexpr double kMeshReachMarginMm = 1.0;

struct MeshPlan {
  slicer::PoseProgram program;      // laps: one per pass; turn_rad 0 (the workpiece has no axis)
  std::size_t restarts = 0;         // passes ended for the arm's range and restarted turned
  double first_rotation_deg = 0.0;  // the first pass's rotation about the nozzle axis
  // The twist about the nozzle axis from the reference pose over the program, deg (the pass's
  // rotation plus what tilting brings about the nozzle axis).
  double rotation_min_deg = 0.0, rotation_max_deg = 0.0;
  double max_tilt_deg = 0.0;  // largest angle between a contact normal and the mesh's facing
  // The program read back by the row rule (slicer/mesh_row_rule.h) as `strand check` reads
  // its CSV: the deposit farthest from its layer's offset surface (distance to the mesh less
  // the offset, mm) and its row, and the largest raise of a deposit above its layer's offset
  // along its normal (where the faceted mesh is concave under the nozzle), mm.
  double worst_offset_mm = 0.0;
  std::size_t worst_offset_row = 0;
  double max_raise_mm = 0.0;
};

// Plans every layer of `placed` (strokes in (u, v), z_mm = nozzle tip offset). Speeds as
// plan_poses's options. Throws InputError ("substrate.mesh = FILE: ...", one line) where the
// pattern leaves the mesh, the nozzle's cone meets it, a point cannot be presented at any
// rotation about the nozzle axis (naming u, v, x, y, z, the layer and why), the program
// would exceed kMaxPosePoints, or a row breaks the row rule as `strand check` would read it
// from the CSV (its first such row with the check's own line).
MeshPlan plan_poses_on_mesh(const slicer::Toolpath& placed, const slicer::MeshSubstrate& s,
                            const machines::RobotCell& cell, const PosePlanOptions& options);

// Reads `plan`'s rows back by the row rule (slicer/mesh_row_rule.h) as `strand check` reads
// its CSV (the CSV's digits, the layers' offsets), sets its worst_offset_mm, worst_offset_row
// and max_raise_mm, and throws InputError with the check's line for the first row the check
// would reject (plan_poses_on_mesh calls it).
void judge_mesh_plan(const slicer::MeshSubstrate& s, MeshPlan& plan);

// Rotation about `up` (unit) of `r` relative to `reference` (both workpiece -> machine), rad:
// the twist part of r * reference^T.
double rotation_about(const Eigen::Matrix3d& r, const Eigen::Matrix3d& reference,
                      const slicer::Vec3& up);

// The reference pose of a mesh in a cell: its facing against the nozzle axis, the workpiece
// z axis (made perpendicular to the facing) along robot.substrate_axis.
Eigen::Matrix3d mesh_reference_rotation(const slicer::Vec3& facing,
                                        const machines::RobotCell& cell);

}  // namespace strand::post
