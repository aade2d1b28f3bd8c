// `strand check` for a pose CSV planned on a robot-held mesh (slicer/mesh_substrate.h): the
// mesh is found from the record written beside the CSV (part.substrate.json: the mesh file
// and its fingerprint, the layer offsets) or given with --substrate-mesh. Every row is read
// back by the rule the planner places it by (slicer/mesh_row_rule.h): deposits on their
// layer's offset surface (kMeshSurfaceMm), travels on or above it, every normal within
// kMeshNormalDeg of the mesh's normal at its foot; strands and crossings are judged per layer
// in the mesh's (u, v). The rows
// against the cell (nozzle tip and axis, speeds, numbering, reach and joints) are checked as
// for a cylinder (pose_check.h).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "machines/profile.h"
#include "postprocess/inspect/pose_check.h"
#include "slicer/mesh_row_rule.h"
#include "slicer/mesh_substrate.h"

namespace strand::post {

using slicer::kMeshNormalDeg;
using slicer::kMeshSurfaceMm;

struct CsvMesh {
  std::string mesh_path;  // from the current directory
  std::optional<slicer::MeshSubstrateRecord> record;
  std::string record_path;  // empty without a record
};

// The mesh of a pose CSV: `given` (--substrate-mesh) when not empty, with the record beside
// the CSV if there is one; else the record's mesh; nullopt when there is neither (a cylinder's
// CSV). Throws InputError for a record that cannot be read.
std::optional<CsvMesh> find_csv_mesh(const std::string& csv_file, const std::string& given);

// The substrate; throws InputError ("substrate.mesh = FILE: ...") when it cannot be read.
std::unique_ptr<slicer::MeshSubstrate> load_csv_mesh(const CsvMesh& m);

// Throws InputError for a file that is not a pose CSV or a machine that is not a robot cell.
PoseCheckReport check_mesh_pose_csv(std::string_view text, const std::string& file,
                                    const machines::MachineProfile& robot_cell,
                                    const CsvMesh& mesh);

}  // namespace strand::post
