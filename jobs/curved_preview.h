// Previews of curved files: a pose CSV or rotary G-code drawn on its cylinder, the paths in
// the viewing frame (axis along x, u = 0 on top) over the cylinder's translucent mesh, through
// the preview room's scene_from_paths; a pose CSV planned on a robot-held mesh (its record
// part.substrate.json beside it) is drawn over that mesh, its outside facing up.
#pragma once

#include <string>
#include <string_view>

#include "postprocess/inspect/curved_files.h"
#include "postprocess/preview/preview_scene.h"
#include "slicer/mesh_substrate.h"

namespace strand::jobs {

// The substrate is drawn when the part knows its cylinder (radius and length > 0), as
// facets within `tolerance_mm` of the surface.
post::PreviewScene curved_scene(const post::CurvedPart& part, double tolerance_mm);

// The part's contact points and `mesh` turned by the mesh's map rotation (its facing up, the
// flange axis along y); `layer_offsets_mm` per layer (from the record).
post::PreviewScene mesh_scene(const post::CurvedPart& part, const slicer::MeshSubstrate& mesh,
                              const std::vector<double>& layer_offsets_mm);

// A curved file by its name and text: a pose CSV with a mesh record beside it on that mesh,
// anything else as curved_scene. Throws InputError as read_curved_part and the mesh reader.
post::PreviewScene curved_file_scene(const std::string& file, std::string_view text,
                                     double tolerance_mm);

}  // namespace strand::jobs
