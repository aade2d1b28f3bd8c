// A substrate mesh as a Surface (surface.h): a disk-like patch of triangles mapped to flat
// pattern coordinates (u, v) in mm, from the mesh's own UVs when it has them, else by a
// CGAL least-squares conformal parameterisation; points by barycentric interpolation on
// the triangle that holds (u, v), normals from smoothed (area-weighted) vertex normals.
#pragma once

#include <memory>
#include <string>

#include "slicer/mesh.h"
#include "slicer/surface.h"

namespace strand::slicer {

// How far the (u, v) map is from preserving lengths, over all triangles: the ratio of a
// triangle's 3D area to its (u, v) area, and the conformal stretch (larger over smaller
// singular value of the map's Jacobian, 1 = no shape change).
struct MapDistortion {
  double area_ratio_min = 1.0;
  double area_ratio_max = 1.0;
  double stretch_max = 1.0;
  bool operator==(const MapDistortion&) const = default;
};

class MeshSurface : public Surface {
 public:
  // `source` names the file in reports and errors. Throws InputError when the mesh is not a
  // disk-like patch (one border, no handles) and has no UVs, or its UVs fold over.
  MeshSurface(const Mesh& mesh, const std::string& source);
  ~MeshSurface() override;
  MeshSurface(const MeshSurface&) = delete;
  MeshSurface& operator=(const MeshSurface&) = delete;

  SurfaceFrame frame_at(const Vec2& uv_mm, double offset_mm) const override;
  UvBox domain() const override;
  std::optional<double> u_period_mm(double) const override { return std::nullopt; }
  bool in_domain(const Vec2& uv_mm) const override;
  std::string kind() const override { return "mesh"; }
  nlohmann::json describe() const override;
  TriangleMesh preview_mesh(double tolerance_mm) const override;

  const MapDistortion& distortion() const;
  // "file UVs" or "least-squares conformal (CGAL)".
  const std::string& uv_source() const;
  // Highest point of the substrate, mm: travels clear it.
  double top_z_mm() const;
  // The welded mesh the map is defined on, and its (u, v) per vertex in mm (same indices):
  // for mapping 3D points on the mesh back to pattern coordinates (mesh_substrate.h).
  const Mesh& mesh() const;
  const std::vector<Vec2>& vertex_uv() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace strand::slicer
