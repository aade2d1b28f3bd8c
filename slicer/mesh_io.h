// Reading part and substrate meshes: STL (ASCII and binary), OBJ, PLY and OFF through
// OpenMesh, glTF and GLB through tinygltf, 3MF through lib3mf; then units, rotation and
// placement.
#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <string>
#include <vector>

#include "slicer/mesh.h"

namespace strand::slicer {

// Triangles accepted after reading (files are bounded by kMaxInputBytes before): no input
// may exhaust memory.
inline constexpr std::size_t kMaxMeshTriangles = 4'000'000;
// Vertices a file may declare (PLY, OFF element counts; 3MF placed copies): three per
// triangle, as in a soup.
inline constexpr std::size_t kMaxMeshVertices = 3 * kMaxMeshTriangles;

// The mesh as stored in the file (file units, file frame). Throws InputError for a missing,
// unreadable, unknown-format, empty or too large file, and for non-finite coordinates.
Mesh read_mesh_file(const std::string& path);
// The objects of a multi-object file, each apart: a 3MF's build items in build order (their
// transforms and the unit applied, as read_mesh_file places them together); any other
// format is one object. The same checks as read_mesh_file.
std::vector<Mesh> read_mesh_objects(const std::string& path);
// The meshes as one (vertices and triangles in order; UVs dropped).
Mesh merge_meshes(const std::vector<Mesh>& meshes);
// `merged` (merge_meshes(like) with its vertices moved) cut back into meshes shaped as `like`.
std::vector<Mesh> split_mesh(const Mesh& merged, const std::vector<Mesh>& like);

enum class Placement {
  Center,  // bounding-box centre at x = y = 0 (the machine's part centre), resting on z = 0
  Origin,  // the file's x/y origin at the part centre, resting on z = 0
};

struct MeshPlacement {
  double mm_per_unit = 1.0;        // --mesh-units: mm 1, cm 10, m 1000, in 25.4
  Vec3 rotate_deg = Vec3::Zero();  // about x, then y, then z (fixed axes, file origin)
  Placement place = Placement::Center;
};

// "mm", "cm", "m", "in" -> mm per unit; throws InputError naming `key` otherwise.
double mm_per_mesh_unit(const std::string& key, const std::string& units);
Placement placement_from(const std::string& key, const std::string& name);
// Scales, rotates and places the mesh as the part frame expects (bottom at z = 0); `applied`
// (may be null) is set to the affine map it applied to every vertex.
Mesh place_mesh(Mesh m, const MeshPlacement& placement, Eigen::Affine3d* applied = nullptr);

// The mesh as a binary STL file's bytes (float coordinates, facet normals from the corners).
std::string binary_stl_bytes(const Mesh& m);

}  // namespace strand::slicer
