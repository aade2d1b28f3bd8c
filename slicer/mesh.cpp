// Measures of a triangle mesh.
#include "slicer/mesh.h"

#include <Eigen/Geometry>
#include <cstdio>

namespace strand::slicer {

Box3 bounds(const Mesh& m) {
  Box3 b;
  if (m.vertices_mm.empty()) return b;
  b.min_mm = b.max_mm = m.vertices_mm.front();
  for (const Vec3& v : m.vertices_mm) {
    b.min_mm = b.min_mm.cwiseMin(v);
    b.max_mm = b.max_mm.cwiseMax(v);
  }
  return b;
}

double signed_volume_mm3(const Mesh& m) {
  double six_v = 0.0;
  for (const auto& t : m.triangles) {
    const Vec3& a = m.vertices_mm[t[0]];
    six_v += a.dot(m.vertices_mm[t[1]].cross(m.vertices_mm[t[2]]));
  }
  return six_v / 6.0;
}

double triangle_double_area_mm2(const Mesh& m, int t) {
  const auto& f = m.triangles[static_cast<std::size_t>(t)];
  const Vec3& a = m.vertices_mm[f[0]];
  return (m.vertices_mm[f[1]] - a).cross(m.vertices_mm[f[2]] - a).norm();
}

double surface_area_mm2(const Mesh& m) {
  double a = 0.0;
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    a += triangle_double_area_mm2(m, static_cast<int>(t));
  return a / 2.0;
}

TriangleMesh to_triangle_mesh(const Mesh& m) { return {m.vertices_mm, m.triangles}; }

std::string point_text(const Vec3& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.3f, %.3f, %.3f)", p.x(), p.y(), p.z());
  return buf;
}

}  // namespace strand::slicer
