// Previews of curved files: a pose CSV or rotary G-code drawn on its cylinder, the paths in
// the viewing frame (axis along x, u = 0 on top) over the cylinder's translucent mesh, through
// the preview room's scene_from_paths.
#pragma once

#include "postprocess/inspect/curved_files.h"
#include "postprocess/preview/preview_scene.h"

namespace strand::cli {

// The substrate is drawn when the part knows its cylinder (radius and length > 0), as
// facets within `tolerance_mm` of the surface.
post::PreviewScene curved_scene(const post::CurvedPart& part, double tolerance_mm);

}  // namespace strand::cli
