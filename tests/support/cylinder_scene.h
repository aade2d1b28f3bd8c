// Test-only: a toolpath laid on a cylinder the simple way, to build 3D preview scenes before
// the planners map toolpaths through a real Surface. The cylinder's axis is the x axis; a
// toolpath point (u, v) maps to arc length u round the cylinder (u = 0 on top, +z) and v
// along the axis; layer k lies (k + 1) * its height out from the surface.
#pragma once

#include "postprocess/preview/preview_scene.h"
#include "slicer/toolpath.h"

namespace strand::testing {

slicer::Vec3 on_cylinder(const slicer::Vec2& uv_mm, double radius_mm);

// The cylinder's side as triangles: `sides` facets round it, from x = -length/2 to +length/2.
slicer::TriangleMesh cylinder_mesh(double radius_mm, double length_mm, int sides);

// Every layer's strokes mapped (pieces of at most 0.5 mm), one path per feature run, the
// cylinder's mesh as the substrate.
post::PreviewScene cylinder_scene(const slicer::Toolpath& t, double radius_mm, double length_mm);

}  // namespace strand::testing
