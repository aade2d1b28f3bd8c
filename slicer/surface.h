// Curved layers: a Surface maps flat pattern coordinates (u, v) in mm and an offset along its
// normal to a 3D point with its unit normal and tangents. Generators stay 2D and exact; the
// planners for curved substrates map strokes through a Surface (the chord error measured on
// the surface), so a cylinder, a mesh patch or any later surface serves every generator and
// every output (pose programs, robot programs, rotary G-code, previews).
#pragma once

#include <array>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "slicer/geometry.h"

namespace strand::slicer {

// The frame of a surface at one pattern point, in the surface's own (workpiece) frame, mm.
struct SurfaceFrame {
  Vec3 point_mm = Vec3::Zero();  // on the surface raised by the offset along the normal
  Vec3 normal = Vec3::UnitZ();   // unit, pointing away from the substrate (to the nozzle)
  // Partial derivatives of point_mm by u and by v (mm per mm of pattern coordinate) at
  // that offset; not unit: their lengths are the local stretch of the mapping.
  Vec3 d_du = Vec3::UnitX();
  Vec3 d_dv = Vec3::UnitY();

  // Unit 3D direction of a pattern direction `uv_direction` (not necessarily unit).
  Vec3 tangent(const Vec2& uv_direction) const {
    return (d_du * uv_direction.x() + d_dv * uv_direction.y()).normalized();
  }
};

// Axis-aligned rectangle of pattern coordinates, mm.
struct UvBox {
  Vec2 min_mm = Vec2::Zero();
  Vec2 max_mm = Vec2::Zero();
  bool contains(const Vec2& uv, double slack_mm = 0.0) const {
    return (uv.array() >= min_mm.array() - slack_mm).all() &&
           (uv.array() <= max_mm.array() + slack_mm).all();
  }
};

// Triangles for previews (the substrate drawn under the path), in the workpiece frame, mm.
struct TriangleMesh {
  std::vector<Vec3> vertices_mm;
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise seen from outside

  bool operator==(const TriangleMesh&) const = default;
};

class Surface {
 public:
  virtual ~Surface() = default;

  // The frame at pattern point `uv_mm`, `offset_mm` along the normal (0 = on the substrate;
  // layer k's nozzle tip is at (k + 1) * layer height, as planar layer k is at z = (k + 1) h).
  // Precondition: in_domain(uv_mm).
  virtual SurfaceFrame frame_at(const Vec2& uv_mm, double offset_mm) const = 0;
  // Where the mapping is defined. A periodic direction (a cylinder's u) reports one period.
  virtual UvBox domain() const = 0;
  // Period of u in mm when the surface closes on itself in u (a cylinder's circumference at
  // the offset where u is measured), else nullopt.
  virtual std::optional<double> u_period_mm(double offset_mm) const = 0;
  // True where frame_at may be called (periodic u wraps).
  virtual bool in_domain(const Vec2& uv_mm) const = 0;
  // Short name for reports and errors: "cylinder", "mesh".
  virtual std::string kind() const = 0;
  // The surface's defining values for reports (radius, length, source file...).
  virtual nlohmann::json describe() const = 0;
  // The substrate as triangles, flat to within `tolerance_mm`, for previews.
  virtual TriangleMesh preview_mesh(double tolerance_mm) const = 0;
};

}  // namespace strand::slicer
