// A substrate mesh held by a robot (`--substrate mesh --substrate-mesh FILE`): the mesh's
// coordinates, in mm, are the workpiece frame on the flange (the frame a cylinder's would be:
// `robot.mount_mm` along flange z, turned by `robot.mount_rotation_deg`), and its outside
// (the side its triangles' counter-clockwise normals point to) faces the nozzle.
//
// As a Surface it maps pattern coordinates (u, v) through a MeshSurface (the file's UVs, or
// CGAL's least-squares conformal map, with its distortion) made in a frame where the mesh's
// mean outward normal (its `facing`) is +z, so any orientation of the mesh in its file works;
// frames come back in the workpiece frame. Normals are the area-weighted vertex normals of
// the outside, interpolated across each triangle; layer k's nozzle tip lies (k + 1) h along
// them. Points can be mapped back (a pose CSV's contact points onto the mesh, for checks),
// and the nozzle's cone tested against the mesh (mesh_collision.h).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "slicer/mesh.h"
#include "slicer/mesh_collision.h"
#include "slicer/mesh_surface.h"
#include "slicer/surface.h"

namespace strand::slicer {

class MeshSubstrate : public Surface {
 public:
  // `source` names the file in reports and errors. Throws InputError ("substrate.mesh =
  // SOURCE: ...") for a mesh without triangles, without an outside that faces one way (a
  // closed mesh), or that MeshSurface refuses (not a disk-like patch and no UVs, folded UVs).
  MeshSubstrate(const Mesh& mesh, const std::string& source);
  ~MeshSubstrate() override;
  MeshSubstrate(const MeshSubstrate&) = delete;
  MeshSubstrate& operator=(const MeshSubstrate&) = delete;

  // Outside the domain: InputError naming the point (a pattern that leaves the mesh).
  SurfaceFrame frame_at(const Vec2& uv_mm, double offset_mm) const override;
  UvBox domain() const override;
  std::optional<double> u_period_mm(double) const override { return std::nullopt; }
  bool in_domain(const Vec2& uv_mm) const override;
  std::string kind() const override { return "mesh"; }
  nlohmann::json describe() const override;
  TriangleMesh preview_mesh(double tolerance_mm) const override;

  const MapDistortion& distortion() const;
  const std::string& uv_source() const;
  const std::string& source() const;
  // Unit mean outward normal (area-weighted), workpiece frame.
  const Vec3& facing() const;
  // Workpiece frame -> the frame the (u, v) map was made in (facing = +z, the workpiece z
  // axis, the flange's, as close to +y as it can be): also the frame previews draw in.
  const Eigen::Matrix3d& map_rotation() const;
  // The welded mesh, workpiece frame.
  const Mesh& mesh() const;

  // A point p mapped back onto the mesh: p = base + offset * normal(base), base on the mesh.
  struct Located {
    Vec3 base_mm = Vec3::Zero();
    Vec3 normal = Vec3::UnitZ();  // the interpolated normal at base
    Vec2 uv_mm = Vec2::Zero();    // pattern coordinates of base
    double offset_mm = 0.0;       // along the normal (negative below the outside)
    double residual_mm = 0.0;     // |p - (base + offset * normal)|: 0 on an offset surface
  };
  Located locate(const Vec3& p_mm) const;
  // Where the line through p along `normal` (unit) meets the mesh: the hit nearest p below it
  // (offset >= 0), else the nearest above it (offset < 0); residual 0. nullopt beside the mesh.
  std::optional<Located> foot_along(const Vec3& p_mm, const Vec3& normal) const;
  // Distance from p to the mesh (its nearest triangle), mm.
  double distance_mm(const Vec3& p_mm) const;

  // A point of the mesh inside the nozzle's cone with its tip at `tip_mm` (workpiece frame)
  // and its axis `up` (unit, against the flow), or nullopt.
  std::optional<Vec3> cone_hit(const NozzleCone& cone, const Vec3& tip_mm, const Vec3& up) const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

// 64-bit FNV-1a of a file's bytes as 16 hex digits: names the mesh a pose CSV was planned on.
std::string content_fingerprint(std::string_view bytes);

// What `strand check` and `strand preview` need to find a pose CSV's mesh: written beside the
// CSV as `part.substrate.json` (mesh_record_path), since the CSV's own header is fixed and the
// Sunrise program reads every row after it.
struct MeshSubstrateRecord {
  std::string mesh;         // the mesh file, relative to the CSV's folder when it can be
  std::string fingerprint;  // content_fingerprint of its bytes
  std::string machine;      // the profile the job was planned for (name or file)
  std::vector<double> layer_offsets_mm;  // nozzle tip above the substrate per layer
  NozzleCone cone;                       // the cone the plan was checked with

  bool operator==(const MeshSubstrateRecord&) const = default;
};

nlohmann::json to_json(const MeshSubstrateRecord& r);
// Throws InputError naming `file` and the key when the record is malformed.
MeshSubstrateRecord mesh_record_from_json(const nlohmann::json& j, const std::string& file);
// part.csv -> part.substrate.json (beside it).
std::string mesh_record_path(const std::string& csv_path);
// The record's mesh as a path from the current directory (relative to the CSV's folder).
std::string mesh_path_from_record(const MeshSubstrateRecord& r, const std::string& csv_path);

}  // namespace strand::slicer
