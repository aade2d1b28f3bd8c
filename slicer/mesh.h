// A triangle mesh as Strand uses it: indexed triangles in mm, optional per-vertex texture
// coordinates, and the measures slicing needs (bounds, volume, area).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "slicer/geometry.h"
#include "slicer/surface.h"

namespace strand::slicer {

struct Mesh {
  std::vector<Vec3> vertices_mm;
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise seen from outside
  std::vector<Vec2> uv;  // per vertex (glTF TEXCOORD_0, OBJ vt); empty when the file has none

  bool operator==(const Mesh&) const = default;
};

struct Box3 {
  Vec3 min_mm = Vec3::Zero();
  Vec3 max_mm = Vec3::Zero();
  Vec3 size_mm() const { return max_mm - min_mm; }
  bool operator==(const Box3&) const = default;
};

Box3 bounds(const Mesh& m);
// Signed volume (divergence theorem); positive for a closed, outward-oriented mesh, mm^3.
double signed_volume_mm3(const Mesh& m);
double surface_area_mm2(const Mesh& m);
// Twice the area of triangle `t`, mm^2 (0 for a degenerate triangle).
double triangle_double_area_mm2(const Mesh& m, int t);
// The mesh as preview triangles (surface.h).
TriangleMesh to_triangle_mesh(const Mesh& m);
// "(x, y, z)" with 3 decimals, for messages that say where.
std::string point_text(const Vec3& p_mm);

}  // namespace strand::slicer
