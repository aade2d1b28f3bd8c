// A curved job on a robot-held mesh up to its writers: read the mesh (the workpiece frame),
// place the pattern on its (u, v) map, plan the pose program (mesh_pose_planner.h), and make
// the report, the file headers and the substrate record written beside the CSV. The robot
// programs themselves are written by produce_curved from the pose program, as for a cylinder.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "machines/profile.h"
#include "postprocess/plan/mesh_pose_planner.h"
#include "slicer/substrate_params.h"
#include "slicer/toolpath.h"

namespace strand::post {

struct MeshJob {
  slicer::Toolpath placed;  // the pattern in the mesh's (u, v)
  MeshPlan plan;
  nlohmann::json report;  // pose_report with the mesh's substrate, placement and passes
  std::vector<std::string> header;
  std::pair<std::string, std::string> record_file;  // part.substrate.json and its text
};

// Throws InputError unless `m` is a robot cell (the robot holds the mesh).
void require_mesh_machine(const machines::MachineProfile& m);

// `t`: the generated pattern in its own frame; `output`: the pose CSV's path. Throws
// InputError for a machine that is not a robot cell, an unreadable or unusable mesh, a
// pattern that leaves the mesh, a collision or a point the arm cannot present.
MeshJob plan_mesh_job(const slicer::Toolpath& t, const slicer::SubstrateSpec& s,
                      const machines::MachineProfile& m, double arc_tolerance_mm,
                      const std::string& output);

// The terminal lines of a mesh job (its report complete with outputs, programs, robot).
std::string mesh_job_summary(const nlohmann::json& report);

}  // namespace strand::post
