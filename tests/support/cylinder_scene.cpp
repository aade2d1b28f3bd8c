// A toolpath on a test cylinder, as a preview scene (tests only).
#include "tests/support/cylinder_scene.h"

#include <cmath>

#include "tests/support/wrap_checks.h"

namespace strand::testing {

using slicer::Vec2;
using slicer::Vec3;

namespace {

Vec3 at_radius(const Vec2& uv, double surface_mm, double radius_mm) {
  const double a = uv.x() / surface_mm;
  return {uv.y(), radius_mm * std::sin(a), radius_mm * std::cos(a)};
}

}  // namespace

Vec3 on_cylinder(const Vec2& uv_mm, double radius_mm) {
  return at_radius(uv_mm, radius_mm, radius_mm);
}

slicer::TriangleMesh cylinder_mesh(double radius_mm, double length_mm, int sides) {
  slicer::TriangleMesh m;
  for (int k = 0; k < sides; ++k) {
    const double a = 2 * M_PI * k / sides;
    for (double x : {-length_mm / 2, length_mm / 2}) {
      m.vertices_mm.emplace_back(x, radius_mm * std::sin(a), radius_mm * std::cos(a));
    }
  }
  for (int k = 0; k < sides; ++k) {
    const int a0 = 2 * k, a1 = a0 + 1, b0 = 2 * ((k + 1) % sides), b1 = b0 + 1;
    m.triangles.push_back({a0, b0, b1});
    m.triangles.push_back({a0, b1, a1});
  }
  return m;
}

post::PreviewScene cylinder_scene(const slicer::Toolpath& t, double radius_mm, double length_mm) {
  std::vector<post::PreviewPath> paths;
  std::vector<double> offsets;
  double width = 0;
  for (std::size_t k = 0; k < t.layers.size(); ++k) {
    const auto& layer = t.layers[k];
    const double r = radius_mm + (static_cast<double>(k) + 1) * layer.height_mm;
    offsets.push_back(r - radius_mm);
    for (const auto& s : layer.strokes) {
      width = std::max(width, s.width_mm);
      Vec2 at = s.start_mm;
      for (const auto& seg : s.segments) {
        slicer::Stroke one;
        one.start_mm = at;
        one.segments = {seg};
        if (paths.empty() || paths.back().feature != seg.feature ||
            paths.back().layer != static_cast<int>(k)) {
          paths.push_back({static_cast<int>(k), seg.feature, false, {at_radius(at, radius_mm, r)}});
        }
        for (const auto& [a, b] : flat_segments(one, 0.01)) {
          const int pieces = std::max(1, static_cast<int>(std::ceil((b - a).norm() / 0.5)));
          for (int i = 1; i <= pieces; ++i) {
            paths.back().points_mm.push_back(at_radius(a + (b - a) * i / pieces, radius_mm, r));
          }
        }
        at = seg.end_mm;
      }
    }
  }
  return post::scene_from_paths(std::move(paths), std::move(offsets),
                                cylinder_mesh(radius_mm, length_mm, 96), width);
}

}  // namespace strand::testing
