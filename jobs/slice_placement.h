// Where a slice put its mesh (issue 34): the report's "mesh_placement" records the affine map
// from the mesh files' coordinates as read to machine coordinates, so a viewer draws the part
// (or the --onto substrate) under the paths from the kept input file without slicing again.
#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "jobs/slice_job.h"
#include "machines/profile.h"
#include "slicer/surface.h"

namespace strand::jobs {

// Triangles a viewer draws of a recorded mesh; a larger one is drawn simplified to this many
// (slicer/mesh_decimate.h), with a note: its index would outgrow the paths' blocks (300k
// triangles are about 8 MB of JSON).
inline constexpr std::size_t kMaxViewerMeshTriangles = 300'000;

// {"role": "part" or "substrate", "files": [...as the parameters name them],
//  "file_to_machine": 4 rows of 4 numbers}: `to_part_frame` (file coordinates as the mesh
// readers return them: file units, a 3MF's build transforms applied, before --up) followed by
// the machine's part centre (the first printhead's coordinates, as in the G-code).
nlohmann::json mesh_placement_json(const std::string& role, const std::vector<std::string>& files,
                                   const Eigen::Affine3d& to_part_frame,
                                   const machines::MachineProfile& machine);
// The files a slice of a part reads, as its parameters name them.
std::vector<std::string> slice_inputs(const SliceSettings& s);

struct PlacedMesh {
  slicer::TriangleMesh mesh;  // machine coordinates (mm); empty when left out
  std::size_t triangles = 0;  // the files' triangles
  std::string note;           // why the mesh was left out, or empty
};

// The mesh a report's "mesh_placement" records, read with the bounded mesh readers and placed:
// each file by its name only inside `folder` (a server's job folder), or with an empty folder
// at its recorded path (`strand preview --mesh-from` on the user's own report); over
// `max_triangles`, drawn simplified with a note. Throws InputError for a malformed record or an
// unreadable file.
PlacedMesh placed_mesh_from(const nlohmann::json& placement, const std::string& folder,
                            std::size_t max_triangles = kMaxViewerMeshTriangles);

}  // namespace strand::jobs
