// Mesh validation and repair for slicing, with CGAL Polygon Mesh Processing: a part must be
// closed, edge-manifold, consistently oriented and free of self-intersections. `--repair`
// stitches borders, fills small holes and re-orients, and reports every change.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "slicer/mesh.h"

namespace strand::slicer {

// Largest hole `--repair` fills, in border edges; bigger openings are design, not damage.
inline constexpr std::size_t kMaxRepairHoleEdges = 2000;

// What is wrong with a (welded) mesh; counts are edges or face pairs, `where` names one
// instance with coordinates (mm).
struct MeshCheck {
  std::size_t border_edges = 0;        // used by one triangle: the mesh is open
  std::size_t non_manifold_edges = 0;  // shared by three or more triangles
  std::size_t misoriented_edges = 0;   // two triangles run the edge the same way
  std::size_t self_intersections = 0;  // pairs of triangles that cut each other
  bool inside_out = false;             // closed and consistent, but normals point inward
  std::string problem;                 // first blocking problem with where, empty = none
  bool ok() const { return problem.empty(); }
};

// Merges coincident vertices (exact: STL stores each triangle's corners separately) and
// drops triangles that collapse; UVs follow their vertices.
Mesh weld_mesh(const Mesh& m);

// Merges coincident vertices (exact), then checks. Self-intersections are searched only
// when the topology is sound.
MeshCheck check_mesh(const Mesh& m);

struct PreparedMesh {
  Mesh mesh;                         // welded, outward oriented, repaired if asked
  std::vector<std::string> changes;  // what was changed, for the report ("stitched 12 ...")
  MeshCheck before;                  // the check of the mesh as read
};

// Welds, checks, repairs when `repair`, orients outward. Throws InputError
// "`what` = path: <problem> at (x, y, z)[; run with --repair]" when the mesh cannot be
// sliced, and for flat or zero-volume meshes.
PreparedMesh prepare_mesh(const Mesh& m, bool repair, const std::string& what);

}  // namespace strand::slicer
