// The motions of a robot program outside its laps, planned and checked: from home by a joint
// move to a clearance pose (robot.clearance_mm from the first pose along the nozzle axis), by
// linear moves to the approach pose (robot.approach_mm) and onto the first pose; at the end
// the same way back (retract, clearance pose, joint move home).
//
// Every one of these motions is checked for the workpiece (the cylinder or mesh the arm
// holds, with the layers already printed) against the nozzle's cone and the extruder's body
// above it (robot.keep_out). A joint move is followed along its joint interpolation through
// the arm's forward kinematics, as the controllers' PTP / movej / MoveAbsJ move: by
// conservative advancement, each step no longer than the clearance the last sample proved
// (no workpiece point moves farther than that), so the whole swept motion is covered, not
// samples of it. A start or end that would collide is replanned with a clearance pose
// farther away (1.5, 2, 3 times) and refused with one line naming the motion when none fits.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "machines/robot_arm.h"
#include "slicer/mesh.h"
#include "slicer/pose_program.h"

namespace strand::machines {

// The workpiece as the transit check sees it: a triangle mesh in the workpiece frame, and
// for a cylinder its solid (a point strictly inside is inside the workpiece).
struct TransitWorkpiece {
  slicer::Mesh mesh;
  std::optional<double> cylinder_radius_mm;  // the mesh is a cylinder about z, 0..length
  double cylinder_length_mm = 0.0;
  double printed_mm = 0.0;  // layers printed at the end: thickness along the normal
};

// A cylinder of radius `radius_mm` (plus `printed_mm`) about the workpiece z axis from 0 to
// `length_mm`, as a closed mesh circumscribing it (its facets never inside the true surface).
TransitWorkpiece cylinder_workpiece(double radius_mm, double length_mm, double printed_mm);
// An open or closed mesh held as it is in the workpiece frame.
TransitWorkpiece mesh_workpiece(slicer::Mesh mesh, double printed_mm);

struct TransitMotion {
  std::string name;    // "home -> clearance pose", "clearance pose -> approach", ...
  bool joint = false;  // joint-interpolated (else linear in the workpiece's pose)
  double min_clearance_mm = 0.0;  // smallest workpiece-to-nozzle distance proved on it
  double at_fraction = 0.0;       // where along the motion (0..1)
  bool near_nozzle = false;       // ends or starts at the nozzle: checked against the cone only
  bool collides = false;
  std::size_t samples = 0;
};

struct TransitPlan {
  std::optional<Joints> home;  // robot.motion.home_joints_deg in rad
  // Start: (home) -PTP-> start_clearance -LIN-> start_approach -LIN-> first pose.
  slicer::PosePoint start_clearance, start_approach;
  Joints start_clearance_joints = Joints::Zero();
  double start_clearance_mm = 0.0;
  // End: last pose -LIN-> end_retract -LIN-> end_clearance -PTP-> (home).
  slicer::PosePoint end_retract, end_clearance;
  Joints end_clearance_joints = Joints::Zero();
  double end_clearance_mm = 0.0;
  std::vector<TransitMotion> motions;  // in program order
  // The smallest clearance over the motions away from the nozzle (all but the final approach
  // and the first retract, which end at the nozzle as a lap does), and which motion.
  double min_clearance_mm = 0.0;
  std::string min_clearance_where;
  bool ok = true;
  std::string problem;  // one line, when !ok: which motion, how deep, what was tried
};

// Plans and checks the start and end of `program` on `cell`. `last_joints`: the arm's joints
// at the last pose as the path leads there (analyse_joints' last solution); without it they
// are solved along the program here. Never throws for a collision: the plan says !ok.
TransitPlan plan_transit(const RobotCell& cell, const slicer::PoseProgram& program,
                         const TransitWorkpiece& workpiece,
                         const std::optional<Joints>& last_joints = std::nullopt);
// The same for rows read back from a pose CSV (strand check).
TransitPlan plan_transit(const RobotCell& cell, const std::vector<slicer::PosePoint>& points,
                         const TransitWorkpiece& workpiece,
                         const std::optional<Joints>& last_joints = std::nullopt);

// The report's "transit" object and its summary line.
nlohmann::json transit_json(const TransitPlan& plan);
std::string transit_text(const TransitPlan& plan);

}  // namespace strand::machines
