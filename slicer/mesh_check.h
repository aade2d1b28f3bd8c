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
  std::size_t self_intersections = 0;  // pairs of triangles that cut each other, when counted
  bool self_intersecting = false;      // some pair cuts (counted or not)
  bool inside_out = false;             // closed and consistent, but normals point inward
  bool touching_vertex = false;        // surfaces meet at a single vertex (non-manifold)
  std::string problem;                 // first blocking problem with where, empty = none
  bool ok() const { return problem.empty(); }
};

// Merges coincident vertices (exact: STL stores each triangle's corners separately) and
// drops triangles that collapse; UVs follow their vertices.
Mesh weld_mesh(const Mesh& m);

// How far check_mesh searches for self-intersections: every pair, counted (what `strand mesh`
// prints), or up to the first (what slicing needs: the soup slicer resolves them all alike, and
// on a part whose shells overlap the count costs most of the time it takes to read it).
enum class Crossings { Count, First };

// Merges coincident vertices (exact), then checks. Self-intersections are searched only
// when the topology is sound.
MeshCheck check_mesh(const Mesh& m, Crossings crossings = Crossings::Count);

// Border, non-manifold and misoriented edges of the mesh as indexed (no welding): what
// `--repair` must never increase.
MeshCheck check_edges_as_indexed(const Mesh& m);

// What `strand mesh` prints: a mesh's measures and defects (edges and vertices after exact
// welding).
struct MeshInfo {
  Vec3 size = Vec3::Zero();                 // bounding box, file units
  std::size_t triangles = 0, vertices = 0;  // as read
  std::size_t shells = 0;                   // connected pieces (through shared vertices)
  std::size_t holes = 0;                    // loops of border edges
  std::size_t non_manifold_vertices = 0;    // where surfaces touch at one vertex
  MeshCheck check;                          // border, non-manifold, misoriented edges; crossings
  bool crossings_searched = false;          // self-intersections are searched when edges are sound
  double volume = 0.0;                      // signed, file units^3
};
MeshInfo mesh_info(const Mesh& m);

struct PreparedMesh {
  Mesh mesh;                         // welded, outward oriented, repaired if asked
  std::vector<std::string> changes;  // what was changed, for the report ("stitched 12 ...")
  std::vector<std::string> defects;  // what was found and how slicing handles it ("mesh: ...")
  MeshCheck before;                  // the check of the mesh as read
};

struct PrepareOptions {
  bool repair = false;  // CGAL soup repair, stitching and hole filling, kept only if no worse
  bool strict = false;  // refuse any defect, as a closed-surface slicer would
};

// Welds, checks, repairs when asked, orients outward. Defects are listed in `defects` (the
// soup slicer of mesh_slicer.h copes with them); with `strict` they throw InputError
// "`what`: <problem> at (x, y, z) (run with --repair to fix it)". Flat meshes and meshes with
// no volume throw in either mode.
PreparedMesh prepare_mesh(const Mesh& m, const PrepareOptions& options, const std::string& what);
// The strict form: prepare_mesh(m, {repair, true}, what).
PreparedMesh prepare_mesh(const Mesh& m, bool repair, const std::string& what);

}  // namespace strand::slicer
