// A mesh made coarse for drawing: vertex clustering (Rossignac and Borrel) on a uniform grid.
// Each vertex goes to the mean of the vertices in its cell and triangles whose corners meet
// are dropped, so a scan of millions of triangles is drawn beside its toolpath in a browser.
// Chosen over edge-collapse simplification (CGAL's Surface_mesh_simplification, OpenMesh's
// Decimater) because those need a manifold surface, which real scans and soups often are
// not; clustering takes any triangles in one pass and never fails. For drawing only: the
// shape is kept to about a cell, not its volume or topology.
#pragma once

#include <cstddef>

#include "slicer/mesh.h"

namespace strand::slicer {

struct Decimated {
  Mesh mesh;
  double cell_mm = 0.0;  // the grid's cell; 0 when the mesh already had few enough triangles
};

// `m` with at most `max_triangles` triangles (max_triangles >= 1): the finest grid that gets
// there, its cell growing by 1.25 from sqrt(2 x surface area / max_triangles).
// Deterministic (cells numbered in vertex order). Uvs are dropped.
Decimated decimate_for_drawing(const Mesh& m, std::size_t max_triangles);

}  // namespace strand::slicer
