// What a mesh's indices alone tell (slicer/mesh_check.h runs them before the geometric
// checks): edges used other than once each way, and vertices whose triangles form more than
// one fan. weld_mesh, declared in mesh_check.h, is defined with them.
#pragma once

#include "slicer/mesh_check.h"

namespace strand::slicer {

// Counts border, non-manifold and misoriented edges into `c` (naming the first of each with
// coordinates) and sets c.problem for the first kind found.
void check_edges(const Mesh& m, MeshCheck& c);

// Whether the triangles around some vertex form more than one fan (surfaces touching at a
// single vertex); meant for a mesh whose edges check_edges finds sound.
bool touches_at_a_vertex(const Mesh& m);

}  // namespace strand::slicer
