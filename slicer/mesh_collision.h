// Proximity on a triangle mesh (a CGAL AABB tree, kept inside mesh_collision.cpp): the closest
// point of the mesh to a point, with its triangle and barycentric weights, and whether the
// outside of a nozzle near its tip (a cone frustum around the nozzle axis) meets the mesh.
// Used for robot-held substrate meshes (mesh_substrate.h): planning refuses a point whose
// nozzle would touch the substrate, and checks map pose rows back onto the mesh.
#pragma once

#include <memory>
#include <optional>

#include "slicer/mesh.h"

namespace strand::slicer {

// The nozzle's outside near the tip: a frustum around the nozzle axis, radius tip_radius_mm
// at the tip, widening at half_angle_deg over length_mm (up the nozzle, against the flow).
struct NozzleCone {
  double half_angle_deg = 30.0;
  double length_mm = 25.0;
  double tip_radius_mm = 1.0;

  bool operator==(const NozzleCone&) const = default;
};

struct MeshPoint {
  Vec3 point_mm = Vec3::Zero();
  int triangle = -1;
  Vec3 barycentric = Vec3(1.0, 0.0, 0.0);  // weights of the triangle's three corners
  double distance_mm = 0.0;                // from the queried point
};

class MeshProximity {
 public:
  // Precondition: `mesh` has at least one triangle.
  explicit MeshProximity(const Mesh& mesh);
  ~MeshProximity();
  MeshProximity(const MeshProximity&) = delete;
  MeshProximity& operator=(const MeshProximity&) = delete;

  MeshPoint closest(const Vec3& p_mm) const;

  // Where the segment from `from_mm` to `to_mm` first meets the mesh (the hit nearest
  // `from_mm`; distance_mm is measured from it), or nullopt when it misses.
  std::optional<MeshPoint> first_hit(const Vec3& from_mm, const Vec3& to_mm) const;

  // A point of the mesh inside `cone` with its tip at `tip_mm` and its axis `up` (unit, from
  // the tip up the nozzle, against the flow), or nullopt when the mesh stays outside. Exact up
  // to 1e-6 mm: every triangle near the cone is clipped to its length and the frustum's
  // (convex) distance function minimised over it.
  std::optional<Vec3> cone_hit(const NozzleCone& cone, const Vec3& tip_mm, const Vec3& up) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace strand::slicer
